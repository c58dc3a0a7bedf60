#include "packbed/sizes.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numeric>
#include <random>

#include <fmt/format.h>

#include "generate/portable_math.hpp"
#include "generate/random.hpp"
#include "packbed/error.hpp"

namespace packbed {

using namespace detail; // the portable elementary functions (generate/portable_math.hpp)

// ---------------------------------------------------------------------------------------------
// The number distribution.

struct NumberDistribution::Impl {
    enum class Form {
        steps,          ///< mono, discrete: m_x the sizes, m_c cumulative number fractions
        linear,         ///< Q0 linear between the nodes (m_x, m_c)
        inverse_square, ///< Q3 linear between the nodes: Q0 linear in d^-2 on each interval;
                        ///< m_c the cumulative number (times low^3) at the nodes
        gaussian,       ///< normal by number: (d - location) / scale truncated standard normal
        log_gaussian,   ///< lognormal: (ln d - location) / scale truncated standard normal
        tabulated,      ///< normal by volume: m_c the integral of q0 at the nodes m_x
    };
    Form form = Form::steps;
    double low = 0.0, high = 0.0;
    std::vector<double> x, c;
    double location = 0.0, scale = 1.0;
    double size_scale = 1.0; ///< tabulated: the lower bound, scaling the density near 1
    TruncatedNormal standard;

    /// The unnormalised q0 of `tabulated`: \f$e^{-((d - \mu)/\sigma)^2/2} (s / d)^3\f$.
    double density(double d) const {
        const double z = (d - location) / scale, r = size_scale / d;
        return exp_portable(-0.5 * z * z) * (r * r * r);
    }
    /// \f$\int_a^b\f$ density: Gauss-Legendre with 8 points (b - a <= 0.1 sigma and 0.05 low).
    double integral(double a, double b) const {
        const double half = 0.5 * (b - a), middle = 0.5 * (a + b);
        double sum = 0.0;
        for (std::size_t i = 0; i < gl8_nodes.size(); ++i)
            sum += gl8_weights[i] *
                   (density(middle - half * gl8_nodes[i]) + density(middle + half * gl8_nodes[i]));
        return half * sum;
    }
    /// The interval k of the nodes with c[k] < target <= c[k + 1] (0 for target <= 0).
    std::size_t interval_of_mass(double target) const {
        const auto it = std::lower_bound(c.begin() + 1, c.end() - 1, target);
        return static_cast<std::size_t>(it - c.begin()) - 1;
    }
    /// The interval k of the nodes with x[k] <= d < x[k + 1] (the last for d = high).
    std::size_t interval_of_diameter(double d) const {
        const auto it = std::upper_bound(x.begin() + 1, x.end() - 1, d);
        return static_cast<std::size_t>(it - x.begin()) - 1;
    }
};

NumberDistribution::NumberDistribution(const SizeDistribution& sizes, FractionBasis basis) {
    auto impl = std::make_shared<Impl>();
    using Form = Impl::Form;
    impl->low = sizes.low;
    impl->high = sizes.high;
    switch (sizes.kind) {
    case SizeKind::mono:
    case SizeKind::discrete: {
        impl->form = Form::steps;
        impl->x = sizes.diameters;
        const auto x = number_fractions(sizes, basis);
        CompensatedSum sum;
        for (const double f : x) {
            sum.add(f);
            impl->c.push_back(std::min(sum.value(), 1.0));
        }
        // The last size with a fraction reaches 1 exactly.
        for (std::size_t k = x.size(); k-- > 0;) {
            impl->c[k] = 1.0;
            if (x[k] > 0.0)
                break;
        }
        break;
    }
    case SizeKind::uniform:
    case SizeKind::file:
        impl->x = sizes.diameters;
        if (basis == FractionBasis::number) {
            impl->form = Form::linear;
            impl->c = sizes.fractions;
        } else {
            // q3 = dF / dd constant on each interval, so q0 = q3 / d^3 integrates to
            // dF (d_i + d_{i+1}) / (2 d_i^2 d_{i+1}^2), here times low^3.
            impl->form = Form::inverse_square;
            CompensatedSum sum;
            impl->c.push_back(0.0);
            for (std::size_t i = 0; i + 1 < impl->x.size(); ++i) {
                const double a = impl->x[i], b = impl->x[i + 1];
                const double ra = sizes.low / a, rb = sizes.low / b;
                sum.add((sizes.fractions[i + 1] - sizes.fractions[i]) * 0.5 * (ra * ra) *
                        (rb * rb) * ((a + b) / sizes.low));
                impl->c.push_back(sum.value());
            }
        }
        break;
    case SizeKind::lognormal: {
        impl->form = Form::log_gaussian;
        impl->scale = log_portable(sizes.spread);
        // Hatch & Choate (1929): q3 lognormal with median M gives q0 lognormal with median
        // M exp(-3 sigma^2), the same sigma.
        impl->location = log_portable(sizes.location) -
                         (basis == FractionBasis::volume ? 3.0 * impl->scale * impl->scale : 0.0);
        impl->standard = TruncatedNormal((log_portable(sizes.low) - impl->location) / impl->scale,
                                         (log_portable(sizes.high) - impl->location) / impl->scale);
        break;
    }
    case SizeKind::normal:
        impl->location = sizes.location;
        impl->scale = sizes.spread;
        if (basis == FractionBasis::number) {
            impl->form = Form::gaussian;
            impl->standard = TruncatedNormal((sizes.low - sizes.location) / sizes.spread,
                                             (sizes.high - sizes.location) / sizes.spread);
        } else {
            // q0 proportional to the normal density over d^3 has no closed form: tabulated at
            // nodes 0.1 sigma and 0.05 low apart at most, from 40 sigma around the mean
            // (beyond, the density is below 1e-347 of its peak).
            impl->form = Form::tabulated;
            const double a = std::max(sizes.low, sizes.location - 40.0 * sizes.spread);
            const double b = std::min(sizes.high, sizes.location + 40.0 * sizes.spread);
            impl->low = a;
            impl->high = b;
            const double step = std::min(0.1 * sizes.spread, 0.05 * a);
            const auto intervals =
                static_cast<std::size_t>(std::clamp(std::ceil((b - a) / step), 1.0, 1e6));
            impl->x.resize(intervals + 1);
            for (std::size_t j = 0; j <= intervals; ++j)
                impl->x[j] =
                    j == intervals
                        ? b
                        : a + (b - a) * (static_cast<double>(j) / static_cast<double>(intervals));
            impl->size_scale = a;
            CompensatedSum sum;
            impl->c.push_back(0.0);
            for (std::size_t j = 0; j < intervals; ++j) {
                sum.add(impl->integral(impl->x[j], impl->x[j + 1]));
                impl->c.push_back(sum.value());
            }
        }
        break;
    }
    m_impl = std::move(impl);
}

double NumberDistribution::cumulative(double diameter) const {
    const Impl& d = *m_impl;
    using Form = Impl::Form;
    if (d.form == Form::steps) {
        const auto k = static_cast<std::size_t>(std::upper_bound(d.x.begin(), d.x.end(), diameter) -
                                                d.x.begin());
        return k == 0 ? 0.0 : d.c[k - 1];
    }
    if (!(diameter > d.low))
        return 0.0;
    if (!(diameter < d.high))
        return 1.0;
    switch (d.form) {
    case Form::linear: {
        const std::size_t i = d.interval_of_diameter(diameter);
        const double w = (diameter - d.x[i]) / (d.x[i + 1] - d.x[i]);
        return std::clamp(d.c[i] + w * (d.c[i + 1] - d.c[i]), 0.0, 1.0);
    }
    case Form::inverse_square: {
        // The part of interval i below d: (a^-2 - d^-2) / (a^-2 - b^-2).
        const std::size_t i = d.interval_of_diameter(diameter);
        const double a = d.x[i], b = d.x[i + 1];
        const double w = ((diameter - a) * (diameter + a) * (b * b)) /
                         ((b - a) * (b + a) * (diameter * diameter));
        return std::clamp((d.c[i] + w * (d.c[i + 1] - d.c[i])) / d.c.back(), 0.0, 1.0);
    }
    case Form::gaussian:
        return d.standard.cumulative((diameter - d.location) / d.scale);
    case Form::log_gaussian:
        return d.standard.cumulative((log_portable(diameter) - d.location) / d.scale);
    case Form::tabulated: {
        const std::size_t i = d.interval_of_diameter(diameter);
        return std::clamp((d.c[i] + d.integral(d.x[i], diameter)) / d.c.back(), 0.0, 1.0);
    }
    case Form::steps:
        break;
    }
    return 0.0;
}

double NumberDistribution::quantile(double fraction) const {
    const Impl& d = *m_impl;
    using Form = Impl::Form;
    const double t = std::clamp(fraction, 0.0, 1.0);
    if (d.form != Form::steps) { // the bounds themselves, not their rounded images
        if (!(t > 0.0))
            return d.low;
        if (!(t < 1.0))
            return d.high;
    }
    switch (d.form) {
    case Form::steps: {
        if (!(t > 0.0))
            return d.low;
        const auto k =
            static_cast<std::size_t>(std::lower_bound(d.c.begin(), d.c.end(), t) - d.c.begin());
        return d.x[std::min(k, d.x.size() - 1)];
    }
    case Form::linear: {
        const std::size_t i = d.interval_of_mass(t);
        const double w = (t - d.c[i]) / (d.c[i + 1] - d.c[i]);
        return std::clamp(d.x[i] + w * (d.x[i + 1] - d.x[i]), d.x[i], d.x[i + 1]);
    }
    case Form::inverse_square: {
        // d^-2 is linear in the mass within an interval.
        const double target = t * d.c.back();
        const std::size_t i = d.interval_of_mass(target);
        const double a = d.x[i], b = d.x[i + 1];
        const double w = std::clamp((target - d.c[i]) / (d.c[i + 1] - d.c[i]), 0.0, 1.0);
        const double r = a / b;
        return std::clamp(a / std::sqrt((1.0 - w) + w * (r * r)), a, b);
    }
    case Form::gaussian:
        return std::clamp(d.location + d.scale * d.standard.quantile(t), d.low, d.high);
    case Form::log_gaussian:
        return std::clamp(exp_portable(d.location + d.scale * d.standard.quantile(t)), d.low,
                          d.high);
    case Form::tabulated: {
        // Newton's method on the integral from the interval's node, kept inside the interval
        // (bisection where a step would leave it). It converges quadratically with an error
        // below (|q0'| / 2 q0) step^2 <= 2 step^2 / width: a step of 1e-9 of the interval's
        // width leaves an error below 2e-18 of it.
        const double target = t * d.c.back();
        const std::size_t i = d.interval_of_mass(target);
        double a = d.x[i], b = d.x[i + 1];
        const double node = a, base = d.c[i], width = b - a;
        double x = a + width * std::clamp((target - base) / (d.c[i + 1] - base), 0.0, 1.0);
        for (int iteration = 0; iteration < 100; ++iteration) {
            const double g = base + d.integral(node, x) - target;
            if (g == 0.0)
                break;
            (g > 0.0 ? b : a) = x;
            const double slope = d.density(x);
            const double step = slope > 0.0 ? g / slope : width;
            if (std::fabs(step) <= 1e-9 * width) { // converged (above): the last step
                x -= step;
                break;
            }
            x = x - step > a && x - step < b ? x - step : 0.5 * (a + b);
            if (!(a < b))
                break;
        }
        return std::clamp(x, d.x[i], d.x[i + 1]);
    }
    }
    return d.low;
}

// ---------------------------------------------------------------------------------------------
// Drawing.

std::vector<double> number_fractions(const SizeDistribution& sizes, FractionBasis basis) {
    if (sizes.kind != SizeKind::mono && sizes.kind != SizeKind::discrete)
        return {};
    std::vector<double> x(sizes.fractions.size());
    CompensatedSum sum;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double r = sizes.diameters[k] / sizes.low; // scaled: no overflow at any size
        x[k] =
            basis == FractionBasis::volume ? sizes.fractions[k] / (r * r * r) : sizes.fractions[k];
        sum.add(x[k]);
    }
    const double total = sum.value();
    for (auto& f : x)
        f /= total;
    return x;
}

std::vector<std::size_t> discrete_counts(const SizeDistribution& sizes, FractionBasis basis,
                                         std::size_t count) {
    const auto x = number_fractions(sizes, basis);
    std::vector<std::size_t> counts(x.size(), 0);
    std::vector<double> remainders(x.size(), 0.0);
    std::size_t given = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double exact = static_cast<double>(count) * x[k];
        counts[k] = std::min(static_cast<std::size_t>(std::floor(exact)), count);
        remainders[k] = exact - std::floor(exact);
        given += counts[k];
    }
    // Largest remainders first, ties to the smaller size (stable order).
    std::vector<std::size_t> order(x.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t i, std::size_t j) { return remainders[i] > remainders[j]; });
    for (std::size_t k = 0; given < count && !order.empty(); k = (k + 1) % order.size()) {
        if (x[order[k]] > 0.0) {
            ++counts[order[k]];
            ++given;
        }
    }
    while (given > count) // only if the floors summed above count through rounding
        for (std::size_t k = order.size(); k-- > 0 && given > count;)
            if (counts[order[k]] > 0) {
                --counts[order[k]];
                --given;
            }
    return counts;
}

std::vector<double> draw_diameters(const SizeDistribution& sizes, std::size_t count,
                                   FractionBasis basis, std::uint64_t seed) {
    if (sizes.kind == SizeKind::mono)
        return std::vector<double>(count, sizes.diameters.front());
    std::vector<double> out;
    out.reserve(count);
    std::mt19937_64 rng(seed);
    if (sizes.kind == SizeKind::discrete) {
        const auto counts = discrete_counts(sizes, basis, count);
        for (std::size_t k = 0; k < counts.size(); ++k)
            out.insert(out.end(), counts[k], sizes.diameters[k]);
    } else {
        const NumberDistribution law(sizes, basis);
        const double n = static_cast<double>(count);
        for (std::size_t i = 0; i < count; ++i)
            out.push_back(
                law.quantile((static_cast<double>(i) + portable_random::uniform01(rng)) / n));
    }
    portable_random::shuffle(std::span<double>(out), rng);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Statistics.

namespace {

void check_diameters(std::span<const double> diameters) {
    for (std::size_t i = 0; i < diameters.size(); ++i)
        if (!(std::isfinite(diameters[i]) && diameters[i] > 0.0))
            throw InvalidInput(fmt::format("size statistics: diameter {} of sphere {} is not "
                                           "allowed; allowed: a finite number > 0",
                                           diameters[i], i + 1));
}

/// size_classes of diameters already sorted and checked.
std::vector<SizeClass> classes_of_sorted(std::span<const double> sorted, std::size_t bins) {
    std::vector<SizeClass> classes;
    if (sorted.empty())
        return classes;
    std::vector<double> distinct;
    for (const double d : sorted) {
        if (distinct.empty() || d != distinct.back())
            distinct.push_back(d);
        if (distinct.size() > max_discrete_classes)
            break;
    }
    if (distinct.size() <= max_discrete_classes) {
        for (const double d : distinct)
            classes.push_back(SizeClass{d, d, 0, 0.0, 0.0});
        return classes;
    }
    bins = std::max<std::size_t>(bins, 1);
    const double smallest = sorted.front(), largest = sorted.back();
    const double log_ratio = log_portable(largest / smallest);
    std::vector<double> edges(bins + 1);
    for (std::size_t j = 0; j <= bins; ++j)
        edges[j] = j == 0      ? smallest
                   : j == bins ? largest
                               : smallest * exp_portable(log_ratio * static_cast<double>(j) /
                                                         static_cast<double>(bins));
    for (std::size_t j = 0; j < bins; ++j)
        classes.push_back(SizeClass{edges[j], edges[j + 1], 0, 0.0, 0.0});
    return classes;
}

} // namespace

std::vector<SizeClass> size_classes(std::span<const double> diameters, std::size_t bins) {
    check_diameters(diameters);
    std::vector<double> sorted(diameters.begin(), diameters.end());
    std::sort(sorted.begin(), sorted.end());
    return classes_of_sorted(sorted, bins);
}

std::size_t size_class_of(std::span<const SizeClass> classes, double diameter) {
    const auto it = std::upper_bound(classes.begin(), classes.end(), diameter,
                                     [](double d, const SizeClass& c) { return d < c.low; });
    return it == classes.begin() ? 0 : static_cast<std::size_t>(it - classes.begin()) - 1;
}

SizeStatistics size_statistics(std::span<const double> diameters, std::size_t bins) {
    check_diameters(diameters);
    SizeStatistics s;
    if (diameters.empty())
        return s;
    std::vector<double> sorted(diameters.begin(), diameters.end());
    std::sort(sorted.begin(), sorted.end());
    s.classes = classes_of_sorted(sorted, bins);
    s.count = sorted.size();
    s.smallest = sorted.front();
    s.largest = sorted.back();
    s.size_ratio = s.largest / s.smallest;

    // Moments, the volume of each class, and Q3 at each distinct diameter.
    CompensatedSum m1, m2, m3, m4;
    std::vector<CompensatedSum> class_volume(s.classes.size());
    std::vector<double> distinct, cumulative;
    std::size_t j = 0;
    for (const double d : sorted) {
        const double d2 = d * d, d3 = d2 * d;
        m1.add(d);
        m2.add(d2);
        m3.add(d3);
        m4.add(d3 * d);
        while (j + 1 < s.classes.size() && d >= s.classes[j + 1].low)
            ++j;
        ++s.classes[j].count;
        class_volume[j].add(d3);
        if (distinct.empty() || d != distinct.back()) {
            distinct.push_back(d);
            cumulative.push_back(0.0);
        }
        cumulative.back() = m3.value();
    }
    const double n = static_cast<double>(s.count), volume = m3.value();
    s.number_mean = m1.value() / n;
    s.sauter_mean = volume / m2.value();
    s.volume_mean = m4.value() / volume;
    CompensatedSum squares;
    for (const double d : sorted)
        squares.add((d - s.number_mean) * (d - s.number_mean));
    s.number_sd = std::sqrt(squares.value() / n);
    for (std::size_t k = 0; k < s.classes.size(); ++k) {
        s.classes[k].number_fraction = static_cast<double>(s.classes[k].count) / n;
        s.classes[k].volume_fraction = class_volume[k].value() / volume;
    }

    // d_p: Q3 is 0 at the smallest diameter, cumulative[i] / volume at distinct[i], linear in
    // between; the first diameter where it reaches p.
    auto at_fraction = [&](double p) {
        for (std::size_t i = 0; i < distinct.size(); ++i) {
            const double q = cumulative[i] / volume;
            if (q >= p) {
                if (i == 0)
                    return distinct[0];
                const double q0 = cumulative[i - 1] / volume;
                return distinct[i - 1] + (p - q0) / (q - q0) * (distinct[i] - distinct[i - 1]);
            }
        }
        return distinct.back();
    };
    s.d10 = at_fraction(0.1);
    s.d50 = at_fraction(0.5);
    s.d90 = at_fraction(0.9);
    return s;
}

nlohmann::json size_statistics_summary(const SizeStatistics& s) {
    nlohmann::json classes = nlohmann::json::array();
    for (const SizeClass& c : s.classes)
        classes.push_back({{"low", c.low},
                           {"high", c.high},
                           {"count", c.count},
                           {"number_fraction", c.number_fraction},
                           {"volume_fraction", c.volume_fraction}});
    return {{"count", s.count},
            {"d10", s.d10},
            {"d50", s.d50},
            {"d90", s.d90},
            {"sauter_mean_d32", s.sauter_mean},
            {"volume_mean_d43", s.volume_mean},
            {"number_mean", s.number_mean},
            {"number_sd", s.number_sd},
            {"smallest", s.smallest},
            {"largest", s.largest},
            {"size_ratio", s.size_ratio},
            {"classes", classes}};
}

} // namespace packbed
