// Structure of a bed of spheres in a cylinder: overall, radial and axial void fraction, the
// radial distribution of centres, contacts and coordination numbers, pair correlation.
// Salvat et al. (2005), sections 1 and 5: every one follows from the sphere positions.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/packing.hpp"
#include "packbed/volume.hpp"

namespace packbed {

/// What to measure and how finely. Lengths marked Dp are in units of the reference diameter
/// (`diameter`, or the mean sphere diameter when not given). Plain value type.
struct AnalysisOptions {
    std::optional<double> diameter; ///< reference diameter Dp (length), 0.1 to 10 times the
                                    ///< mean diameter; default: the mean diameter
    double band_clearance = 1.0;    ///< the axial band keeps this far from floor and top, Dp
    /// The axial band itself (length), instead of band_clearance: z_low < z_high, within the
    /// bed (0 to its top).
    std::optional<Band> band;
    double shell_width = 0.02;       ///< width of the cylindrical shells of e(r), Dp
    double slab_height = 0.05;       ///< height of the slabs of e(z), Dp
    double centre_bin = 0.02;        ///< bin width of the centre distribution, Dp
    double contact_tolerance = 1e-3; ///< a gap below this counts as a contact, Dp
    double rdf_range = 3.0;          ///< g(r) is computed for centre distances up to this, Dp
    double rdf_bin = 0.02;           ///< bin width of g(r), Dp
};

/// One bin of a profile: the interval [low, high] (radius or height, length) and its value.
struct ProfileBin {
    double low = 0.0;
    double high = 0.0;
    double value = 0.0;
};

/// Contacts and coordination of the spheres whose centre lies in the band.
struct Coordination {
    double mean = 0.0;                     ///< mean number of sphere-sphere contacts per sphere
    double mean_without_rattlers = 0.0;    ///< the same over spheres that are not rattlers
    std::size_t rattlers = 0;              ///< spheres with fewer than 4 contacts, the wall counted
    std::size_t spheres = 0;               ///< spheres counted (centre in the band)
    std::vector<std::size_t> histogram;    ///< histogram[k]: spheres with k sphere-sphere contacts
    std::size_t wall_contacts = 0;         ///< spheres of the whole bed touching the lateral wall
    std::size_t wall_contacts_in_band = 0; ///< of which with their centre in the band
};

/// Everything analyze_bed measures.
struct BedAnalysis {
    double diameter = 0.0;      ///< the reference diameter Dp used (length)
    Band band;                  ///< the axial band the properties refer to (length)
    double void_fraction = 0.0; ///< overall, exact, in the band
    std::vector<ProfileBin> radial_void_fraction; ///< e(r) over cylindrical shells, wall first
    std::vector<ProfileBin> axial_void_fraction;  ///< e(z) over slabs from the floor to the top
    std::vector<ProfileBin> centre_distribution;  ///< relative centre density against r
    Coordination coordination;
    std::vector<ProfileBin> pair_correlation; ///< g(r) against centre distance
};

/// Measure a bed in a cylinder.
///
/// - Void fractions are exact: sphere volumes cut by the band planes and by cylinders come from
///   sphere_volume_in_cylinder_slab (closed forms and converged quadrature, no sampling). The
///   radial profile uses shells of `shell_width` starting at the wall (the innermost one may be
///   narrower); each sphere's shell volumes are differences of its volume inside successive
///   cylinders, so they add up to its volume in the band to rounding.
/// - The centre distribution is the number density of centres (in the band) in each annulus,
///   divided by the mean number density of centres over the whole cross-section: 1 for a
///   uniform distribution, 0 where no centre can be (r > Rt - Dp/2).
/// - A contact is a pair with gap |x_i - x_j| - r_i - r_j <= contact_tolerance; a wall contact
///   is Rt - (rho_i + r_i) <= contact_tolerance. A rattler has fewer than 4 contacts, counting
///   the wall as one.
/// - g(r): pairs with the first sphere in the band, normalised by the mean number density of
///   centres in the band and the shell volume 4 pi r^2 dr. Not corrected for the container
///   boundary, so it falls below 1 at distances comparable to the container radius.
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
/// \param container the cylinder (radius > 0, at most limits::max_length)
/// \param options see AnalysisOptions (widths and the range > 0, tolerances >= 0)
/// \return the measurements. \throws InvalidInput for an empty bed, a band that is empty, a
/// value outside the ranges above, or a bed beyond the limits.
BedAnalysis analyze_bed(const Packing& packing, const Cylinder& container,
                        const AnalysisOptions& options = {});

} // namespace packbed
