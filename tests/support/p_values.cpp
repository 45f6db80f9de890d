#include "support/p_values.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace spectrace::testing {

double chiSquareUpperTail(double statistic, double degreesOfFreedom) {
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(degreesOfFreedom), statistic));
}

double studentTUpperTail(double t, double degreesOfFreedom) {
  return boost::math::cdf(boost::math::complement(boost::math::students_t(degreesOfFreedom), t));
}

}  // namespace spectrace::testing
