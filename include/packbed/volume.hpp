// Exact volumes of spheres cut by a cylinder and by horizontal planes (a cone's: cone.hpp; a
// bed's void fraction from them: bed_volume.hpp). "Exact" means closed forms where the cut is by
// planes only, and a converged quadrature of the circle-circle lens area where the cylinder wall
// cuts the sphere (20-point Gauss-Legendre in a variable that smooths the end points; relative
// error of a wall-cut volume below 1e-8): never random sampling.
#pragma once

#include "packbed/container.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// Area of the intersection of two disks.
/// \f$A = r_1^2\arccos(d_1/r_1) - d_1\sqrt{r_1^2-d_1^2} + r_2^2\arccos(d_2/r_2) -
/// d_2\sqrt{r_2^2-d_2^2}\f$ with \f$d_1 = (d^2+r_1^2-r_2^2)/(2d)\f$, \f$d_2 = d - d_1\f$
/// (standard circle-circle lens).
/// \param r1,r2 disk radii (>= 0) \param distance distance between the centres (>= 0)
/// \return the area (length^2); pi min(r1,r2)^2 when one disk lies inside the other.
double disk_intersection_area(double r1, double r2, double distance);

/// Volume of the part of a sphere that lies inside the infinite vertical cylinder
/// x^2 + y^2 <= cylinder_radius^2 and between the planes z = z_low and z = z_high.
/// Exact: planes-only pieces by the spherical-segment formula, wall-cut pieces by converged
/// quadrature of disk_intersection_area over z (smooth inside each piece; relative error
/// below 1e-8).
/// \param center sphere centre \param radius sphere radius (> 0)
/// \param cylinder_radius radius of the cylinder about the z axis (> 0)
/// \param z_low,z_high the slab (z_low <= z_high; an empty slab gives 0)
/// \return the volume (length^3), between 0 and 4/3 pi radius^3.
double sphere_volume_in_cylinder_slab(const Vec3& center, double radius, double cylinder_radius,
                                      double z_low, double z_high);

/// Volume of the sphere of radius `radius` centred at height z_center between the planes
/// z = z_low and z = z_high, with no lateral cut (spherical segments):
/// \f$\int \pi (r^2 - t^2)\,dt\f$ over the heights t from the centre inside both.
double sphere_slab_volume(double z_center, double radius, double z_low, double z_high);

/// Volume of the ball of radius r, its centre at distance rho from the z axis, inside the
/// infinite cylinder of radius cylinder_radius > 0 about that axis (no planes). By cylindrical
/// shells of radius q about the ball's vertical axis, each of height 2 sqrt(r^2 - q^2): the
/// shells wholly inside (q <= Rc - rho) in closed form, 4 pi / 3 (r^3 - (r^2 - q^2)^(3/2)), the
/// shells the wall cuts (|Rc - rho| < q < Rc + rho) by a 20-point Gauss-Legendre rule after
/// the map q = m - h cos u, over theta(q) q 2 sqrt(r^2 - q^2), theta(q) = 2 acos((rho^2 - Rc^2 +
/// q^2) / (2 rho q)) the angle of the circle of radius q inside the wall. It agrees with
/// sphere_volume_in_cylinder_slab to 2.6e-9 relative over 4 000 random balls, half within 1e-8
/// to 1 of the wall (test_analysis), and is 5 times faster than it for one the wall cuts.
double ball_volume_in_cylinder(double rho, double r, double cylinder_radius);

/// Area of the disk of radius `radius` centred at the origin inside the rectangle
/// [x_low, x_high] x [y_low, y_high], in closed form: inclusion-exclusion over the four
/// "lower-left" regions {x <= a, y <= b}, each an integral of the chord
/// \f$2\sqrt{R^2 - x^2}\f$ clipped at y = b, with antiderivative
/// \f$\frac12 (x\sqrt{R^2 - x^2} + R^2 \arcsin(x/R))\f$.
double disk_rectangle_area(double radius, double x_low, double x_high, double y_low, double y_high);

/// Volume of a sphere inside an axis-aligned box. Exact: a ball wholly inside or cut only by
/// the planes z = const uses the spherical-segment formula; otherwise the closed-form
/// disk_rectangle_area of each horizontal slice is integrated over z by tanh-sinh quadrature
/// (relative tolerance 1e-12 asked; up to 4e-10 relative, 6e-11 of r^3, measured against a
/// 30-digit quadrature, docs/voxels.md) on the pieces between the heights where a slice's
/// circle touches an edge line of the box or passes through a corner. ball_box_volume
/// (voxel.hpp) is the closed form, exact to rounding.
/// \param center,radius the sphere (radius > 0) \param low,high the box corners (low <= high)
double sphere_volume_in_box(const Vec3& center, double radius, const Vec3& low, const Vec3& high);

} // namespace packbed
