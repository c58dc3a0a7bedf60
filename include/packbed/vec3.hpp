// Small 3-vector value type for the arithmetic on positions and displacements.
#pragma once

#include <cmath>

namespace packbed {

/// A point or displacement in 3-D space. Plain value type; safe to copy between threads.
struct Vec3 {
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;

    constexpr Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr Vec3& operator-=(const Vec3& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    constexpr Vec3& operator*=(double s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) {
    return a += b;
}
constexpr Vec3 operator-(Vec3 a, const Vec3& b) {
    return a -= b;
}
constexpr Vec3 operator*(Vec3 a, double s) {
    return a *= s;
}
constexpr Vec3 operator*(double s, Vec3 a) {
    return a *= s;
}
constexpr Vec3 operator-(const Vec3& a) {
    return {-a.x, -a.y, -a.z};
}
constexpr double dot(const Vec3& a, const Vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr double norm2(const Vec3& a) {
    return dot(a, a);
}
inline double norm(const Vec3& a) {
    return std::sqrt(norm2(a));
}
inline bool is_finite(const Vec3& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

} // namespace packbed
