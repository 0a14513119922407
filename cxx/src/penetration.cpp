#include <hypercontact/penetration.hpp>

namespace hypercontact {

Penetration penetration(double gap, double smoothing) {
  const double d = smoothing;
  if (d > 0) {
    if (gap >= d) return {0.0, 0.0};
    if (gap > -d) return {(d - gap) * (d - gap) / (4 * d), -(d - gap) / (2 * d)};
    return {-gap, -1.0};
  }
  if (gap > 0) return {0.0, 0.0};
  return {-gap, -1.0};
}

double penetration_energy(double gap, double smoothing) {
  const double d = smoothing;
  if (d > 0) {
    if (gap >= d) return 0.0;
    if (gap > -d) return (d - gap) * (d - gap) * (d - gap) / (12 * d);
    return 0.5 * gap * gap + d * d / 6;
  }
  return gap > 0 ? 0.0 : 0.5 * gap * gap;
}

}  // namespace hypercontact
