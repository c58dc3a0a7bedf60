// Structure of a bed of spheres in a container: overall, wall (radial) and axial void
// fraction, the distribution of centres from the wall, contacts and coordination numbers, pair
// correlation.
// Salvat et al. (2005), sections 1 and 5: every one follows from the sphere positions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "packbed/bed_volume.hpp"
#include "packbed/container.hpp"
#include "packbed/packing.hpp"
#include "packbed/pellet_shape.hpp"
#include "packbed/sizes.hpp"
#include "packbed/volume.hpp"

namespace packbed {

/// What to measure and how finely. Lengths marked Dp are in units of the reference diameter
/// (`diameter`, or the mean sphere diameter when not given). Plain value type.
struct AnalysisOptions {
    std::optional<double> diameter; ///< reference diameter Dp (length), 0.1 to 10 times the
                                    ///< mean diameter; default: the mean diameter (by
                                    ///< number: bins stay fine for the smaller spheres of a
                                    ///< mixture, which d32 would not keep)
    double band_clearance = 1.0;    ///< the axial band keeps this far from floor and top, Dp
    /// The axial band itself (length), instead of band_clearance: z_low < z_high, within the
    /// bed (0 to its top).
    std::optional<Band> band;
    double shell_width = 0.02;       ///< width of the shells of e(d) (d from the wall), Dp
    double slab_height = 0.05;       ///< height of the slabs of e(z), Dp
    double centre_bin = 0.02;        ///< bin width of the centre distribution, Dp
    double contact_tolerance = 1e-3; ///< a gap below this counts as a contact, Dp
    /// The contacts between spheres have friction: a rattler has fewer than 2 contacts, not 4
    /// (Coordination::rattler_contacts).
    bool frictional = false;
    double rdf_range = 3.0; ///< g(r) is computed for centre distances up to this, Dp
    /// rdf_range was asked for: beyond a periodic cell's smaller period it is refused, where the
    /// default is shortened to it (with_fitted_rdf_range)
    bool rdf_range_given = false;
    double rdf_bin = 0.02; ///< bin width of g(r), Dp
};

/// One bin of a profile: the interval [low, high] (length: the distance from the wall for the
/// wall profiles, the height for the axial one, the centre distance for g(r)) and its value.
struct ProfileBin {
    double low = 0.0;
    double high = 0.0;
    double value = 0.0;
};

/// Contacts and coordination of the spheres whose centre lies in the band.
struct Coordination {
    double mean = 0.0;                  ///< mean number of sphere-sphere contacts per sphere
    double mean_without_rattlers = 0.0; ///< the same over spheres that are not rattlers
    std::size_t rattlers = 0;           ///< spheres with fewer than rattler_contacts contacts
    /// A sphere with fewer contacts than this, the wall counted as one, is a rattler: it bears no
    /// load. Without friction 4: forces along the normals hold a sphere in place only when its
    /// contacts cage it, which takes at least d + 1 = 4 of them. With friction 2: two contacts
    /// whose forces lie in their friction cones can balance each other, one cannot.
    std::size_t rattler_contacts = 4;
    std::size_t spheres = 0;               ///< spheres counted (centre in the band)
    std::vector<std::size_t> histogram;    ///< histogram[k]: spheres with k sphere-sphere contacts
    std::size_t wall_contacts = 0;         ///< spheres of the whole bed touching the lateral wall
    std::size_t wall_contacts_in_band = 0; ///< of which with their centre in the band
};

/// The profiles and contacts measured from one wall of the container (Container::profile_walls):
/// the cylinder's or the box's one wall, each wall of an annulus.
struct WallAnalysis {
    std::string name; ///< "wall", or "outer" / "inner" for an annulus
    /// e(d) over shells of the distance d from this wall, from the wall to the container's
    /// depth (an annulus: to the middle of the gap, each wall its own half)
    std::vector<ProfileBin> void_fraction;
    /// the density of the centres (in the band) in this wall's part of the cross-section
    /// against d, over the mean density across the whole cross-section
    std::vector<ProfileBin> centre_distribution;
    std::size_t wall_contacts = 0;         ///< spheres of the whole bed touching this wall
    std::size_t wall_contacts_in_band = 0; ///< of which with their centre in the band
};

/// The region where the centres of the pairs that g(r) counts lie: the container shrunk by the
/// mean radius R (for a cylinder, the cylinder of radius Rt - R) between the heights of `band`.
/// g(r) counts the pairs whose two centres lie in the band and normalises by the volume of each
/// shell inside this region (analyze_bed; docs/analysis.md, "Pair correlation g(r)").
struct PairRegion {
    Container container = Container::tube(0.0); ///< the container shrunk by the mean radius R
    Band band; ///< the heights: the analysis band, within R and top - R (length)
};

/// The region of g(r) for a bed: where the centres of spheres of radius R can be without
/// crossing the wall, the floor or the bed's top (the container shrunk by R, heights from
/// R to top - R), within the analysis band; R is the mean radius of the spheres whose centre
/// lies in the band. For a bed of one size that is where every centre lies (up to the overlap a
/// soft-sphere bed allows, 1e-4 Dp); for mixed sizes the mean radius is an approximation
/// (centres of smaller spheres lie up to R - r_min beyond it, those of larger ones cannot reach
/// it). The one place this choice is made.
/// \param packing the spheres \param container the container \param band the analysis band
/// \return the region; it is empty (depth 0, or z_high <= z_low) when no centre of that
/// radius fits in the container or in the band without crossing the wall, floor or top.
PairRegion pair_region(const Packing& packing, const Container& container, const Band& band);

/// Volume of the part of the ball of radius `radius` around `centre` that lies inside
/// `region` (its container and between its band's heights): what g(r) normalises by.
/// Container::ball_volume: in a cylinder, a ball the band's planes do not cut goes to
/// ball_volume_in_cylinder (cylindrical shells about the ball's own axis, 5 times faster), one
/// they cut to sphere_volume_in_cylinder_slab; in a box, sphere_volume_in_box.
/// \return the volume (length^3), 0 <= V <= 4/3 pi radius^3.
double ball_volume_in_pair_region(const Vec3& centre, double radius, const PairRegion& region);

/// One size class of a bed of many sizes: what segregation and the mixture's
/// structure are read from.
struct SizeClassAnalysis {
    double low = 0.0;               ///< smallest diameter of the class (length)
    double high = 0.0;              ///< largest (a discrete size: low == high)
    std::uint64_t spheres = 0;      ///< spheres of the bed in the class
    double number_fraction = 0.0;   ///< their share of the spheres
    double volume_fraction = 0.0;   ///< their share of the solid volume
    std::size_t in_band = 0;        ///< of them, with their centre in the band
    double mean_coordination = 0.0; ///< mean sphere-sphere contacts of those, any partner's size
    /// the density of the class's centres against the distance from the wall over their own
    /// mean density across the cross-section (bins of centre_bin, as the bed's); for a
    /// container of one wall only (empty for an annulus and a periodic cell)
    std::vector<ProfileBin> centre_distribution;
};

/// Everything analyze_bed measures.
struct BedAnalysis {
    double diameter = 0.0;      ///< the reference diameter Dp used (length)
    Band band;                  ///< the axial band the properties refer to (length)
    double void_fraction = 0.0; ///< overall, exact, in the band
    /// e(d) over shells of the distance d from the wall (cylindrical shells in a cylinder,
    /// rectangular frames in a box), wall first: walls[0].void_fraction for a container of
    /// one wall; empty for an annulus (see walls) and a periodic cell
    std::vector<ProfileBin> radial_void_fraction;
    std::vector<ProfileBin> axial_void_fraction; ///< e(z) over slabs from the floor to the top
    /// relative centre density against d: walls[0].centre_distribution for a container of one
    /// wall; empty otherwise
    std::vector<ProfileBin> centre_distribution;
    /// every wall's profiles and contacts, in the order of Container::profile_walls (none in
    /// a periodic cell)
    std::vector<WallAnalysis> walls;
    Coordination coordination;
    std::vector<ProfileBin> pair_correlation; ///< g(r) against centre distance
    PairRegion pair_region;                   ///< the region g(r) was normalised in (pair_region)
    /// the size classes (sizes.hpp's size_classes: one per distinct diameter up to 32, else
    /// bins even in ln d); empty for a bed of one size
    std::vector<SizeClassAnalysis> by_size;
    /// the statistics of the bed's diameters (d10, d50, d90 by volume, d32, ...) when it has
    /// more than one size; count 0 otherwise
    SizeStatistics sizes;
};

/// Measure a bed in a container (any shape converts to one).
///
/// - The wall profiles, centre distributions and wall contacts are measured from each wall of
///   Container::profile_walls: the one wall of a cylinder or a box (BedAnalysis's
///   radial_void_fraction and centre_distribution are then that wall's), the tube and the rod
///   of an annulus separately (each from its wall to the middle of the gap), none in a
///   periodic cell, which has the overall and axial void fraction, contacts and g(r) only.
/// - In a periodic cell the contacts and g(r) count every copy of a sphere within the
///   distance (the minimum image for distances below half a period; Periodic::separation):
///   the contact distance 2 r_max + tolerance and --rdf-range must not exceed the smaller
///   period.
///
/// - Void fractions are exact: sphere volumes cut by the band planes and by the container come
///   from Container::sphere_volume (closed forms and converged quadrature, no sampling). The
///   wall profile is against the distance d from the nearest wall, in shells of `shell_width`
///   starting at the wall (the innermost one may be narrower): cylindrical shells in a
///   cylinder, rectangular frames in a box (a corner's points count with the face they are
///   nearer to). Each sphere's shell volumes are differences of its volume inside the container
///   shrunk by successive distances, so they add up to its volume in the band to rounding.
/// - The centre distribution is the number density of centres (in the band) in each shell of
///   d, divided by the mean number density of centres over the whole cross-section: 1 for a
///   uniform distribution, 0 where no centre can be (d < Dp/2).
/// - A contact is a pair with gap |x_i - x_j| - r_i - r_j <= contact_tolerance; a wall contact
///   is d_i - r_i <= contact_tolerance (in a cylinder Rt - (rho_i + r_i)). A rattler has fewer than
///   4 contacts, counting the wall as one; 2 in a frictional bed (Coordination::rattler_contacts).
/// - g(r), corrected for the container: g(r) = sum_i n_i(r) / (rho_c sum_i V_i(r)), over the
///   N centres i in the band; n_i counts the other centres in the band at a distance in the
///   bin [r, r + dr), V_i is the volume of the shell [r, r + dr) around centre i that lies
///   inside the region where centres can be (pair_region: the band, and the container shrunk
///   by the mean radius R), rho_c = (N - 1) / |region| the density of the other centres.
///   An ideal gas of points in the region gives 1 in expectation at every r, however narrow the
///   container. V_i(r) = V(r + dr) - V(r) from ball_volume_in_pair_region. The cost is one
///   volume per bin and counted sphere where the shell crosses the wall or a band plane
///   (quadrature, 0.3-0.5 us each), a closed form where it does not: N x bins x the fraction
///   cut, like the radial profile's N x (sphere diameter / shell width).
/// - Contacts and g(r) come from a cell grid searched without storing the pairs (memory O(N)):
///   spheres up to the mean diameter search the 27 cells around their own, a larger sphere the
///   cells its reach needs, so one huge sphere costs about N distance checks, not N per sphere.
/// - The work is bounded by what the input justifies (limits.hpp, where the reasons are): per
///   profile at most max(min_profile_bins, profile_bins_per_sphere N) bins, today
///   max(1e6, 100 N); per pair search at most max(min_pair_checks, pair_checks_per_sphere N
///   max(1, (c / D)^3)) distance checks, c the search distance and D the mean diameter; a
///   reference diameter within max_reference_diameter_ratio (10) of the mean diameter. Beyond
///   them the bed is refused before any work, naming the option to change (--slab-height,
///   --shell-width, --centre-bin, --rdf-bin, --rdf-range, --container-radius, --diameter) or
///   the sphere that makes the bed too tall.
/// \param packing the spheres (any order; coordinates and radii within limits::max_length)
/// \param container the container (radius or widths > 0, within limits::max_length)
/// \param options see AnalysisOptions (widths and the range > 0, tolerances >= 0)
/// \return the measurements. \throws InvalidInput for an empty bed, a band that is empty, a
/// value outside the ranges above, a bed beyond the limits, or a periodic cell narrower than
/// the contact distance or the range of g(r).
BedAnalysis analyze_bed(const Packing& packing, const Container& container,
                        const AnalysisOptions& options = {});

/// The orientation of the pellets whose centroid lies between two distances from the wall:
/// cos(theta) is the component of a pellet's axis along the container's axis z, cos(psi) its
/// component along the wall's normal at the centroid (the direction in which the distance from
/// the wall grows fastest: the radius in a tube).
struct OrientationBin {
    double low = 0.0, high = 0.0; ///< distances of the centroids from the wall (length)
    std::uint64_t pellets = 0;    ///< pellets with their centroid in the band and the bin
    double mean_cos2 = 0.0;       ///< <cos^2 theta>: 1/3 for random orientations
    double order = 0.0; ///< S = (3 <cos^2 theta> - 1) / 2: 1 upright, -1/2 lying, 0 random
    /// <cos^2 psi>: 1 when every axis points at the wall (an end facing it), 0 when every axis
    /// lies parallel to it (upright or level along it), 1/3 at random; 0 without one wall
    double mean_cos2_wall = 0.0;
};

/// What analyze_pellet_bed measures.
struct PelletAnalysis {
    double diameter = 0.0;      ///< d_v, the pellets' reference size (length)
    Band band;                  ///< the axial band (length)
    double void_fraction = 0.0; ///< overall, exact, in the band
    /// e(d) over shells from the wall, as BedAnalysis's (a container of one wall; else empty)
    std::vector<ProfileBin> radial_void_fraction;
    std::vector<ProfileBin> axial_void_fraction; ///< e(z) over slabs from the floor to the top
    /// the axes' orientation against the centroid's distance from the wall, bins of 0.1 d_v (a
    /// container of one wall; else empty)
    std::vector<OrientationBin> orientation;
    OrientationBin overall; ///< every pellet with its centroid in the band
    /// Contacts per pellet (`spheres` counts the pellets with their centroid in the band):
    /// pairs whose exact gap (the shape's pair_gap) is at most contact_tolerance d_v, and
    /// the pellets as close to a side wall. A rattler touches nothing (rattler_contacts 1): a
    /// pellet's count does not say how many points hold it (a face lying on another is one
    /// contact), so the spheres' rule of 4 does not carry over.
    Coordination coordination;
};

/// Measure a bed of pellets (r = d_v / 2, an orientation each) in a container: the void
/// fractions with the exact volumes (the shape's volume_in, volume_from_wall: the same
/// shells, slabs and band as analyze_bed, in units of d_v) and the orientation of the axes
/// against the distance from the wall; the contacts per pellet. \throws InvalidInput for an empty
/// bed, a bed without orientations or a band that is empty
PelletAnalysis analyze_pellet_bed(const Packing& packing, const PelletShape& shape,
                                  const Container& container, const AnalysisOptions& options = {});

} // namespace packbed
