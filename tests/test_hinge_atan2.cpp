static const char help[] = "The hinges' branch-free atan2 (HingeAtan2Wide) against the true angle (long double atan2l) and\n"
                           "libm's atan2, in ulps of the result: on a grid of angles around the circle (every octant and its\n"
                           "edges, the reduction's threshold tan(pi/12)), random points over eight decades of |x|, |y|, and the\n"
                           "axes (y = +-0, x = +-0), which it gives as libm does. Also HingeAtan2 (the series where it holds).\n";
#include "test_util.h"
#include <turgor/physics/hinge_moments.h>
#include <cfloat>
#include <vector>

namespace {

/* |a - truth| in ulps of the double nearest the truth */
double Ulps(double a, long double truth)
{
  const double t = (double)truth, ulp = std::nextafter(std::fabs(t), (double)INFINITY) - std::fabs(t);
  return (double)(std::fabs((long double)a - truth) / (long double)(t == 0 ? DBL_TRUE_MIN : ulp));
}

} // namespace

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  std::vector<std::pair<double, double>> pts; /* (y, x) */
  for (int k = 0; k < 72000; k++) {           /* every 0.005 degrees */
    const double th = -M_PI + 2 * M_PI * (k + 0.5) / 72000;
    pts.push_back({std::sin(th), std::cos(th)});
  }
  for (double th0 : {0.0, M_PI / 12, M_PI / 4, 5 * M_PI / 12, M_PI / 2, 3 * M_PI / 4, M_PI}) /* the edges, a few ulps either side */
    for (int s : {-1, 1})
      for (int j = -20; j <= 20; j++) {
        const double th = s * th0 + j * 1e-15;
        pts.push_back({std::sin(th), std::cos(th)});
      }
  turgor_test::Random rnd(7);
  for (int k = 0; k < 200000; k++) pts.push_back({rnd() * std::pow(10.0, 4 * rnd()), rnd() * std::pow(10.0, 4 * rnd())});
  for (double z : {0.0, -0.0})
    for (double o : {1.0, -1.0, 3e-7, -2e5}) pts.push_back({z, o}), pts.push_back({o, z});
  double worst = 0, worst_libm = 0, worst_small = 0, wy = 0, wx = 0;
  for (auto [y, x] : pts) {
    const long double truth = std::atan2((long double)y, (long double)x);
    const double      e     = Ulps(turgor::HingeAtan2Wide(y, x), truth);
    if (e > worst) worst = e, wy = y, wx = x;
    worst_libm = std::max(worst_libm, Ulps(std::atan2(y, x), truth));
    if (x > 0 && std::fabs(y) <= 0.1 * x) worst_small = std::max(worst_small, Ulps(turgor::HingeAtan2(y, x), truth));
    /* the signs and the axes exactly as libm (but (0, 0), which a hinge never has) */
    if (y == 0 || x == 0) {
      const double a = turgor::HingeAtan2Wide(y, x), b = std::atan2(y, x);
      TG_CHECK(a == b && std::signbit(a) == std::signbit(b), "atan2(%g, %g): %.17g against libm's %.17g", y, x, a, b);
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "%zu points: HingeAtan2Wide within %.2f ulp of the truth (worst at y = %.17g, x = %.17g), libm within %.2f; the series within %.2f\n",
                        pts.size(), worst, wy, wx, worst_libm, worst_small));
  TG_CHECK(worst <= 3.0, "HingeAtan2Wide is %.2f ulp off at y = %.17g, x = %.17g", worst, wy, wx);
  TG_CHECK(worst_small <= 2.5, "HingeAtan2's series is %.2f ulp off", worst_small);
  PetscCall(PetscFinalize());
  return 0;
}
