// LDGF against the analytic slope of the paper's synthetic objects (PhantomGenerator ground truth).
#include "vtouchHapticsTestUtilities.h"
#include "vtouchLdgfForceLaw.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchTracer.h"

#include <gtest/gtest.h>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

struct AccuracyResult
{
  int checked = 0;
  double worstRelative = 0.0;  ///< |F.eta_a / k - tan(beta)| / |tan(beta)| where |tan(beta)| > 0.05
  double worstAbsolute = 0.0;  ///< same difference where |tan(beta)| <= 0.05
  double worstDirection = 0.0; ///< |F x eta_a| / |F|
};

/// Places the agent on every point away from the path ends whose projected tangent is at least
/// half its length (away from cusps) and compares the LDGF with k tan(beta) from the analytic
/// tangent: tan(beta) = d(depth)/dl = -T.z / |T.xy| for a camera looking down -z.
AccuracyResult compare(PhantomShape shape)
{
  PhantomSpec spec;
  spec.shape = shape;
  PhantomGenerator phantom(spec);
  EXPECT_TRUE(phantom.ok()) << phantom.error();
  const QSkeleton& s = phantom.centerline();
  const Vec3 centre{ 47.5, 47.5, 47.5 };
  auto vm = buildView(s, topCamera(centre, 0.25));
  Tracer tracer;
  LdgfForceLaw law;
  AccuracyResult r;
  const double k = 1.0;
  for (int g = 0; g < vm->pointCount(); ++g)
  {
    const SceneTopology& topo = vm->topology();
    const int i = topo.pointOf(g);
    const int n = topo.pathEnd(topo.pathOf(g)) - topo.pathBegin(topo.pathOf(g));
    const Vec3 t = topo.tangent_World(g);
    const double txy = std::hypot(t.x, t.y);
    const bool closed = s.paths[topo.pathOf(g)].tail.junction >= 0;
    if (txy < 0.5 || (!closed && (i < 8 || i > n - 9)))
    {
      continue;
    }
    const double tanBeta = -t.z / txy;
    const Vec2 etaA{ t.x / txy, t.y / txy };
    tracer.placeAt(*vm, g);
    ForceInput in;
    in.view = vm.get();
    in.state = InteractionState::Tracing;
    in.agent = tracer.sample(*vm);
    in.zoneGain_N = k;
    ForceRequest req;
    const Vec2 f = law.compute(in, req);
    const double along = f.dot(etaA) / k;
    const double diff = std::fabs(along - tanBeta);
    if (std::fabs(tanBeta) > 0.05)
    {
      r.worstRelative = std::max(r.worstRelative, diff / std::fabs(tanBeta));
    }
    else
    {
      r.worstAbsolute = std::max(r.worstAbsolute, diff);
    }
    if (f.norm() > 1e-3)
    {
      r.worstDirection =
        std::max(r.worstDirection, std::fabs(f.x * etaA.y - f.y * etaA.x) / f.norm());
    }
    ++r.checked;
  }
  return r;
}

TEST(LdgfAccuracy, MatchesAnalyticTanBetaOnHelixCircleAndWindingLine)
{
  for (PhantomShape shape :
    { PhantomShape::Helix, PhantomShape::Circle, PhantomShape::WindingLine })
  {
    const AccuracyResult r = compare(shape);
    std::printf("[ accuracy ] %-12s points %5d  worst relative %.4f  worst absolute %.5f  worst "
                "direction %.5f\n",
      toString(shape),
      r.checked,
      r.worstRelative,
      r.worstAbsolute,
      r.worstDirection);
    // The winding line is steep (tan(beta) up to pi): fewer of its points are away from cusps.
    EXPECT_GT(r.checked, shape == PhantomShape::WindingLine ? 100 : 500) << toString(shape);
    EXPECT_LT(r.worstRelative, 0.02) << toString(shape);
    EXPECT_LT(r.worstAbsolute, 0.02 * 0.05) << toString(shape);
    EXPECT_LT(r.worstDirection, 0.02) << toString(shape);
  }
}

} // namespace
} // namespace vtouch
