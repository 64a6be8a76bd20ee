// Private helpers of the mesh code: compensated summation, number formatting.
// (Own namespace: other parts of magFoam may have their own "detail" helpers.)
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace mag::meshDetail {

// Neumaier's compensated sum: the error of a sum of n terms stays at a few ulp of
// the largest partial sum instead of growing with n, which keeps volumes and
// inertia of large meshes (and of meshes whose terms cancel) accurate.
class CompensatedSum {
public:
    void add(double x) {
        const double t = sum_ + x;
        if (std::abs(sum_) >= std::abs(x))
            compensation_ += (sum_ - t) + x;
        else
            compensation_ += (x - t) + sum_;
        sum_ = t;
    }
    double value() const { return sum_ + compensation_; }

private:
    double sum_ = 0.0;
    double compensation_ = 0.0;
};

// Shortest readable form for messages: 9 significant digits, "%g" style, so
// 1e-6 m^3 does not print as 0.000000.
inline std::string formatNumber(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", x);
    return buffer;
}

} // namespace mag::meshDetail
