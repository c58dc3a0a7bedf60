// The highest value of a function over a cylinder's or a ring's surface (cylinder_shape.cpp):
// how a ring, which no finite union of convex pieces makes, finds its depth in another body.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "packbed/cylinder_shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed::detail {

/// The highest value found and where, in the body frame at size 1.
struct SurfacePeak {
    double value = -std::numeric_limits<double>::infinity();
    Vec3 point;
};

/// Golden-section search for the highest f on [lo, hi], `iterations` steps: (t, f(t)) of the
/// better of its last two points.
template <class F>
std::pair<double, double> golden_highest(F&& f, double lo, double hi, int iterations) {
    constexpr double ratio = 0.6180339887498949;
    double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    double f1 = f(x1), f2 = f(x2);
    for (int it = 0; it < iterations; ++it) {
        if (f1 < f2) {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + ratio * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - ratio * (hi - lo);
            f1 = f(x1);
        }
    }
    return f1 >= f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

/// The highest f(q) over the surface of `s` (the body frame at size 1; f changes at most as
/// fast as q moves, as a signed distance does). The surface as four families of circles about
/// the axis, each along one parameter t: the side (radius R, t = z from -L/2 to L/2), a ring's
/// bore (radius R_i) and the two ends (z = +-L/2, t = the radius from R_i, or 0, to R); the
/// rims are the families' ends. Each circle is sampled at 64 angles and each sampled local
/// maximum within half a step's arc of the best refined by golden-section search; each family
/// at rows at most 0.1 apart (the rims among them), and each row that is a local maximum within
/// half a row's step of the best refined by golden-section search over t, the angle searched
/// again about the row's best at each t. A maximum narrower than the samples' steps can be
/// missed: the tests compare it with a fine brute force.
template <class F> SurfacePeak highest_on_surface(const CylinderShape& s, F&& f) {
    constexpr int around = 64;
    constexpr double step = 2.0 * std::numbers::pi / around;
    constexpr double row_step = 0.1;
    constexpr int iterations = 40, nested = 28;
    struct Family {
        bool side;
        double fixed, t0, t1; ///< the side's radius or the end's z; t's range
    };
    const double h = s.half_length;
    std::vector<Family> families{{true, s.radius, -h, h}};
    if (s.bore > 0.0)
        families.push_back({true, s.bore, -h, h});
    families.push_back({false, -h, s.bore, s.radius});
    families.push_back({false, h, s.bore, s.radius});
    SurfacePeak best;
    for (const Family& fam : families) {
        const auto point = [&fam](double t, double theta) {
            const double r = fam.side ? fam.fixed : t;
            return Vec3{r * std::cos(theta), r * std::sin(theta), fam.side ? t : fam.fixed};
        };
        const auto consider = [&](double t, double theta, double value) {
            if (value > best.value)
                best = {value, point(t, theta)};
        };
        // The best angle on the circle at t: (theta, value).
        const auto on_circle = [&](double t) {
            std::array<double, around> values;
            std::pair<double, double> top{0.0, -std::numeric_limits<double>::infinity()};
            for (int k = 0; k < around; ++k) {
                values[k] = f(point(t, k * step));
                if (values[k] > top.second)
                    top = {k * step, values[k]};
            }
            const double radius = fam.side ? fam.fixed : t;
            if (!(radius > 0.0))
                return top;
            const double probe = top.second - 0.5 * step * radius;
            for (int k = 0; k < around; ++k) {
                const double here = values[k];
                if (here < probe || here < values[(k + around - 1) % around] ||
                    here < values[(k + 1) % around])
                    continue;
                const auto found = golden_highest([&](double a) { return f(point(t, a)); },
                                                  (k - 1) * step, (k + 1) * step, iterations);
                if (found.second > top.second)
                    top = found;
            }
            return top;
        };
        const int rows = std::max(2, static_cast<int>(std::ceil((fam.t1 - fam.t0) / row_step)));
        const double dt = (fam.t1 - fam.t0) / rows;
        std::vector<std::pair<double, double>> found(static_cast<std::size_t>(rows) + 1);
        double top = -std::numeric_limits<double>::infinity();
        for (int j = 0; j <= rows; ++j) {
            const double t = j == rows ? fam.t1 : fam.t0 + j * dt;
            found[j] = on_circle(t);
            consider(t, found[j].first, found[j].second);
            top = std::max(top, found[j].second);
        }
        for (int j = 0; j <= rows; ++j) {
            const double here = found[j].second;
            if (here < top - 0.5 * dt || (j > 0 && here < found[j - 1].second) ||
                (j < rows && here < found[j + 1].second))
                continue;
            const double theta = found[j].first;
            double best_theta = theta;
            const auto row = [&](double t) {
                const auto a = golden_highest([&](double x) { return f(point(t, x)); },
                                              theta - step, theta + step, nested);
                best_theta = a.first;
                return a.second;
            };
            const double lo = j > 0 ? fam.t0 + (j - 1) * dt : fam.t0;
            const double hi = j < rows ? std::min(fam.t1, fam.t0 + (j + 1) * dt) : fam.t1;
            const auto t = golden_highest(row, lo, hi, nested);
            const double value = row(t.first);
            consider(t.first, best_theta, value);
        }
    }
    return best;
}

} // namespace packbed::detail
