// A parametric curve's arc length tabulated on a fine grid of its parameter, and the parameter at
// an arc length by linear interpolation in the table: how the phantoms' samplers
// (vtouchPhantomShapes.cxx, vtouchVascularTreeGenerator.cxx) place points at equal arc steps.
#pragma once

#include "vtouchVector.h"

#include <algorithm>
#include <vector>

namespace vtouch
{

class ArcLengthTable
{
public:
  /// `at(t)`: the curve's point (mm) at parameter t; [t0, t1] is cut into `fine` equal steps.
  template <class Curve>
  ArcLengthTable(const Curve& at, double t0, double t1, int fine)
    : T0(t0)
    , T1(t1)
    , Fine(std::max(1, fine))
    , Arc_mm(static_cast<std::size_t>(this->Fine) + 1, 0.0)
  {
    Vec3 previous = at(t0);
    for (int i = 1; i <= this->Fine; ++i)
    {
      const Vec3 p = at(t0 + (t1 - t0) * i / this->Fine);
      this->Arc_mm[i] = this->Arc_mm[i - 1] + (p - previous).norm();
      previous = p;
    }
  }

  double length_mm() const { return this->Arc_mm.back(); }

  /// The parameter at arc length `s_mm` (0..length_mm()). A cursor walks the table: successive
  /// calls must not decrease `s_mm` (the samplers go from the start to the end).
  double parameterAt(double s_mm)
  {
    while (this->Cursor < this->Fine - 1 && this->Arc_mm[this->Cursor + 1] < s_mm)
    {
      ++this->Cursor;
    }
    const double span = this->Arc_mm[this->Cursor + 1] - this->Arc_mm[this->Cursor];
    const double w = span > 0.0 ? std::clamp((s_mm - this->Arc_mm[this->Cursor]) / span, 0.0, 1.0)
                                : 0.0;
    return this->T0 + (this->T1 - this->T0) * (this->Cursor + w) / this->Fine;
  }

private:
  double T0, T1;
  int Fine;
  std::vector<double> Arc_mm;
  int Cursor = 0;
};

} // namespace vtouch
