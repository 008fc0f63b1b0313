// TubeSectionTracker's sections and tube following (vtouchTubeSectionParts.h).
#include "vtouchTubeSectionParts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace vtouch
{
namespace tube_sections
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

/// Arcs of `on` around the circle, counting only arcs of >= 2 rays once single-ray gaps are
/// bridged (a lone ray is noise: one voxel of background noise inside a contact, or one ray
/// slipping between two voxels of the wall).
int arcCount(const std::vector<char>& on)
{
  const std::size_t n = on.size();
  std::vector<char> m(on);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!on[k] && on[(k + n - 1) % n] && on[(k + 1) % n])
    {
      m[k] = 1;
    }
  }
  std::vector<char> cleaned(m);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (m[k] && !m[(k + n - 1) % n] && !m[(k + 1) % n])
    {
      cleaned[k] = 0;
    }
  }
  int arcs = 0;
  bool any = false;
  for (std::size_t k = 0; k < n; ++k)
  {
    any = any || cleaned[k];
    if (cleaned[k] && !cleaned[(k + n - 1) % n])
    {
      ++arcs;
    }
  }
  return any && arcs == 0 ? 1 : arcs; // all on: one arc around
}

} // namespace

/// Ray lengths (voxels) of the section through `c` in the plane (u, v): the foreground's run from
/// c along u cos a + v sin a, + half a step; 0 when c is outside. Capped at cap_voxels.
void sectionRays(const SectionSampler& sampler,
  const Vec3& c,
  const Vec3& u,
  const Vec3& v,
  double cap_voxels,
  const Settings& s,
  std::vector<double>& rho)
{
  const double voxel = sampler.voxel_mm();
  const int n = std::max(8, s.rays);
  rho.assign(static_cast<std::size_t>(n), 0.0);
  if (!sampler.inside(c))
  {
    return;
  }
  const double step = s.rayStep_voxels * voxel;
  for (int k = 0; k < n; ++k)
  {
    const double a = 2.0 * kPi * k / n;
    const Vec3 dir = u * std::cos(a) + v * std::sin(a);
    rho[static_cast<std::size_t>(k)] =
      (sampler.runLength(c, dir, cap_voxels * voxel, step) + 0.5 * step) / voxel;
  }
}

double median(std::vector<double> x)
{
  if (x.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const std::size_t m = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(m), x.end());
  const double hi = x[m];
  if (x.size() % 2 == 1)
  {
    return hi;
  }
  return 0.5 * (hi + *std::max_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(m)));
}

double lowerQuartile(std::vector<double> x)
{
  if (x.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const std::size_t q = x.size() / 4;
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(q), x.end());
  return x[q];
}

/// The centre of the tube of radius r (voxels) in the section through p normal to t: the circle of
/// radius r fitted to the ends of the wall rays (ending within r + margin), re-taken from the new
/// centre up to four times. False when the section from the centre is not a tube touched at most
/// on one side (see the header).
bool centreOnTube(const SectionSampler& sampler,
  const Vec3& p,
  const Vec3& tangent,
  double r,
  const Settings& s,
  Vec3& centre,
  bool* touched)
{
  Vec3 t, u, v;
  SectionSampler::sectionBasis(tangent, t, u, v);
  const int n = std::max(8, s.rays);
  const double voxel = sampler.voxel_mm();
  const double cap = r + s.wallMargin_voxels + 3.0;
  std::vector<double> rho;
  Vec3 c = p;
  if (!sampler.inside(c))
  {
    // A thin tube's prediction can leave its lumen: start from the nearest foreground of the
    // section within r + 1 voxel (rings every half voxel, 16 directions).
    bool found = false;
    for (double ring = 0.5; !found && ring <= r + 1.0 + 1e-9; ring += 0.5)
    {
      for (int k = 0; !found && k < 16; ++k)
      {
        const double a = 2.0 * kPi * k / 16;
        const Vec3 q = p + (u * std::cos(a) + v * std::sin(a)) * (ring * voxel);
        if (sampler.inside(q))
        {
          c = q;
          found = true;
        }
      }
    }
    if (!found)
    {
      return false;
    }
  }
  for (int outer = 0; outer < 4; ++outer)
  {
    sectionRays(sampler, c, u, v, cap, s, rho);
    std::vector<std::array<double, 2>> wall;
    for (int k = 0; k < n; ++k)
    {
      const double rk = rho[static_cast<std::size_t>(k)];
      if (rk > 0.0 && rk <= r + s.wallMargin_voxels)
      {
        const double a = 2.0 * kPi * k / n;
        wall.push_back({ rk * std::cos(a), rk * std::sin(a) });
      }
    }
    if (static_cast<double>(wall.size()) < s.minimumWallFraction * n)
    {
      return false;
    }
    // Gauss-Newton for min sum (|w - x| - r)^2 over x in the plane (voxels, relative to c).
    double x[2] = { 0.0, 0.0 };
    for (int it = 0; it < 8; ++it)
    {
      const double radius = r;
      double h00 = 1e-6, h01 = 0.0, h11 = 1e-6, g0 = 0.0, g1 = 0.0;
      for (const auto& w : wall)
      {
        const double dx = x[0] - w[0], dy = x[1] - w[1];
        const double d = std::max(1e-9, std::hypot(dx, dy));
        const double j0 = dx / d, j1 = dy / d, res = d - radius;
        h00 += j0 * j0;
        h01 += j0 * j1;
        h11 += j1 * j1;
        g0 += j0 * res;
        g1 += j1 * res;
      }
      const double det = h00 * h11 - h01 * h01;
      if (!(std::abs(det) > 1e-12))
      {
        break;
      }
      const double s0 = -(h11 * g0 - h01 * g1) / det;
      const double s1 = -(h00 * g1 - h01 * g0) / det;
      x[0] += s0;
      x[1] += s1;
      if (std::hypot(s0, s1) < 1e-3)
      {
        break;
      }
    }
    const Vec3 moved = c + (u * x[0] + v * x[1]) * voxel;
    const bool settled = std::hypot(x[0], x[1]) < 0.05;
    c = moved;
    if (settled)
    {
      break;
    }
  }
  sectionRays(sampler, c, u, v, cap, s, rho);
  int wallRays = 0;
  std::vector<char> runsOn(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k)
  {
    const double rk = rho[static_cast<std::size_t>(k)];
    wallRays += std::abs(rk - r) <= s.wallMargin_voxels ? 1 : 0;
    runsOn[static_cast<std::size_t>(k)] = rk > r + s.wallMargin_voxels ? 1 : 0;
  }
  if (!sampler.inside(c) || static_cast<double>(wallRays) < s.minimumWallFraction * n ||
      arcCount(runsOn) > 1)
  {
    return false;
  }
  centre = c;
  if (touched)
  {
    *touched = arcCount(runsOn) > 0;
  }
  return true;
}

bool inZone(const std::vector<Zone>& zones, const Vec3& p)
{
  for (const Zone& z : zones)
  {
    if ((p - z.centre).norm() <= z.radius)
    {
      return true;
    }
  }
  return false;
}

/// Follows the tube of radius r (voxels) from `start` along `direction` (see the header).
Track follow(const SectionSampler& sampler,
  const Vec3& start,
  const Vec3& direction,
  double r,
  const std::vector<Target>& targets,
  const std::vector<Zone>& zones,
  double maximumLength_mm,
  const Settings& s)
{
  const double voxel = sampler.voxel_mm();
  const double step = s.trackStep_voxels * voxel;
  const double reach = std::max(s.targetReach_voxels, 0.5 * r) * voxel;
  const int lag = std::max(1, static_cast<int>(std::lround(2.0 / s.trackStep_voxels)));
  Track track;
  track.centres.push_back(start);
  Vec3 t = direction * (1.0 / std::max(1e-12, direction.norm()));
  Vec3 c = start;
  double length = 0.0;
  // Coasting: where the section is not a tube's for a step (a branch leaves, a junction), the
  // track goes on straight, through a junction's zone and up to max(1 voxel, r) beyond, and
  // re-centres after it; it ends where the section stays un-tube-like, back at its last centred
  // point.
  const double coastLimit = std::max(1.0, r) * voxel;
  double coasted = 0.0;
  std::size_t lastCentred = 0;
  // Confirmation (confirmedPart): after a coast outside a junction's zone, the centres are the
  // tube's for sure only from an untouched section on; a coast that began in a junction's zone
  // (the track crossing the junction) loses nothing.
  bool sure = true, coastFromZone = false;
  double lengthAtLastCentred = 0.0;
  while (length < maximumLength_mm)
  {
    const Vec3 predicted = c + t * step;
    Vec3 next;
    bool touched = false;
    const bool fitted = centreOnTube(sampler, predicted, t, r, s, next, &touched) &&
                        (next - predicted).norm() <= (0.5 * r + s.maximumShift_voxels) * voxel;
    if (!fitted)
    {
      if ((coasted + step > coastLimit + 1e-9 && !inZone(zones, predicted)) ||
          !sampler.inside(predicted))
      {
        track.centres.resize(lastCentred + 1);
        length = lengthAtLastCentred;
        break;
      }
      coasted = inZone(zones, predicted) ? 0.0 : coasted + step;
      coastFromZone = coastFromZone || inZone(zones, predicted);
      if (sure && !coastFromZone)
      {
        sure = false;
        track.confirmed = lastCentred + 1;
      }
      next = predicted;
    }
    else
    {
      coasted = 0.0;
      const Vec3 back = track.centres[static_cast<std::size_t>(
        std::max(0, static_cast<int>(track.centres.size()) - lag))];
      Vec3 heading = next - back;
      const double hn = heading.norm();
      if (hn > 1e-9)
      {
        heading = heading * (1.0 / hn);
        if (heading.dot(t) < s.maximumTurnCosine)
        {
          track.centres.resize(lastCentred + 1);
          break;
        }
        t = heading;
      }
    }
    length += (next - c).norm();
    c = next;
    track.centres.push_back(c);
    if (fitted)
    {
      lastCentred = track.centres.size() - 1;
      lengthAtLastCentred = length;
      coastFromZone = false;
      sure = sure || !touched;
      if (sure)
      {
        track.confirmed = track.centres.size();
      }
    }
    double best = reach;
    for (const Target& target : targets)
    {
      const double d = (target.position - c).norm();
      if (d <= best)
      {
        best = d;
        track.hit = target.index;
      }
    }
    if (track.hit >= 0)
    {
      break;
    }
  }
  if (track.hit < 0 && track.centres.size() > lastCentred + 1)
  {
    track.centres.resize(lastCentred + 1); // ran out of length while coasting
  }
  (void)length;
  track.confirmed = std::min(track.confirmed, track.centres.size());
  return track;
}

Track confirmedPart(const Track& track)
{
  Track part = track;
  part.centres.resize(std::max<std::size_t>(1, std::min(track.confirmed, track.centres.size())));
  part.confirmed = part.centres.size();
  return part;
}

/// Points every voxel along the polyline from `from` through `via` to `to` (both ends excluded;
/// `to` may be omitted: then up to the polyline's last point, included).
std::vector<Vec3> resampled(const Vec3& from,
  const std::vector<Vec3>& via,
  const Vec3* to,
  double spacing_mm)
{
  std::vector<Vec3> line{ from };
  line.insert(line.end(), via.begin(), via.end());
  if (to)
  {
    line.push_back(*to);
  }
  double total = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i)
  {
    total += (line[i] - line[i - 1]).norm();
  }
  std::vector<Vec3> out;
  if (total <= 1e-9)
  {
    return out;
  }
  // Equal steps no longer than the spacing, so the ends are not crowded.
  const int pieces = std::max(1, static_cast<int>(std::ceil(total / spacing_mm - 1e-9)));
  const double stepLength = total / pieces;
  std::size_t seg = 1;
  double before = 0.0; // arc length at line[seg - 1]
  for (int q = 1; q <= pieces; ++q)
  {
    if (q == pieces && to)
    {
      break; // `to` itself stays the path's own point
    }
    const double at = q * stepLength;
    while (seg + 1 < line.size() && before + (line[seg] - line[seg - 1]).norm() < at)
    {
      before += (line[seg] - line[seg - 1]).norm();
      ++seg;
    }
    const double len = (line[seg] - line[seg - 1]).norm();
    const double f = len > 1e-12 ? std::clamp((at - before) / len, 0.0, 1.0) : 1.0;
    out.push_back(line[seg - 1] + (line[seg] - line[seg - 1]) * f);
  }
  return out;
}

} // namespace tube_sections
} // namespace vtouch
