#pragma once
// Upper-tail p-values of the test statistics the Monte Carlo tests compute.
// Boost.Math's distributions are compiled here once: its headers took
// seconds to parse in every test file that included them.
namespace spectrace::testing {

// P(X >= statistic) for X chi-square distributed with the given degrees of freedom.
double chiSquareUpperTail(double statistic, double degreesOfFreedom);
// P(T >= t) for T Student-t distributed with the given degrees of freedom.
double studentTUpperTail(double t, double degreesOfFreedom);

}  // namespace spectrace::testing
