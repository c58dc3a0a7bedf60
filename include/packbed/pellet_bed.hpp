// Beds of pellets (docs/pellets.md): rigid, oriented particles poured into a container and
// settled by the soft-contact energy of the sphere beds generalised to rigid bodies. A
// cylinder's, a ring's or a multilobe's surface is a set of nodes (ParticleShape's
// SurfaceNode), each pressed out of a neighbour or a wall by a linear spring on how deep it
// lies inside (the level-set contact of Kawamoto et al. 2016); a spherocylinder's contact is
// one linear spring on its exact penetration depth, as a sphere's. FIRE relaxes positions and
// orientations together.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/packing.hpp"
#include "packbed/pellet_shape.hpp"
#include "packbed/soft_sphere.hpp"

namespace packbed {

/// Every parameter of a pellet bed. Lengths in units of the pellet's volume-equivalent
/// diameter d_v (the bed's reference size: a = D_tube / d_v). Plain value type.
struct PelletBedParameters {
    std::uint64_t particles = 100; ///< >= 1
    std::uint64_t seed = 1;        ///< seed of the positions and orientations at insertion
    /// The pellet at size 1 (volume-equivalent radius 1): a cylinder
    /// (MultilobeShape::cylinder(CylinderShape::of_aspect(L / D))), a ring, a multilobe
    /// (MultilobeShape::of) or a spherocylinder (SpherocylinderShape::of_aspect).
    PelletShape shape = MultilobeShape::cylinder(CylinderShape::of_aspect(1.0));
    /// The container in units of d_v (Container::tube(a)).
    Container container = Container::tube(8.0);
    /// The void fraction of the column the pellets are poured from (the paper's e0 of eq. 6).
    /// They are placed apart (their bounding spheres, random sequential addition), so it is
    /// loose: 0.87 at L = D leaves their bounding spheres (1.9 times a pellet's volume) a
    /// quarter of the column, below where such addition jams (a ring's, whose sphere holds
    /// more, is loosened to the same quarter); (0, 1).
    double e0 = 0.87;
    /// The largest allowed final penetration depth, pair and wall, in units of the pellet's
    /// smallest dimension min(D, L) (a ring's min(L, (D - DI) / 2), its wall; a
    /// spherocylinder's D); (0, 0.1].
    double tolerance = 1e-3;
    /// The settling band of the gravity control, in the same units as the tolerance: the
    /// largest depth is held between them until the mass centre stops.
    double band_low = 1.5e-2, band_high = 3e-2;
    /// The nodes' spacing on the surface, d_v; [0.01, 0.2].
    double node_spacing = 0.05;
    /// The largest force (and torque over the bounding radius) left on a pellet at the end, in
    /// units of its weight; (0, 1].
    double force_tolerance = 1e-2;
    std::uint64_t max_steps = 2'000'000; ///< give up (ConvergenceError) beyond this
    /// Coulomb's friction coefficient between pellets and between a pellet and the walls and
    /// floor (docs/generate.md, "Friction"): tangential springs at the contacts, capped by mu
    /// times the normal load; 0, the default, is the frictionless bed; [0, 100].
    double friction = 0.0, wall_friction = 0.0;
    /// Each pellet's size over the reference pellet's (the `shape` at size 1, d_v = 1), in
    /// insertion order: pellet i is the shape scaled by scales[i] (docs/generate.md, "Sizes of
    /// pellets"). Empty: every pellet 1. Else one per pellet, each finite and > 0, the largest
    /// over the smallest at most max_size_ratio. The tolerance, the settling band and the
    /// nodes' spacing hold for the smallest and the largest pellet alike: the depths are
    /// measured against the smallest pellet's smallest dimension, the nodes placed at the
    /// spacing on the largest.
    std::vector<double> scales;
    /// A bed whose column (the height the pellets are inserted over) exceeds twice this, d_v,
    /// is relaxed in layers of about this height (docs/generate.md, "Tall pellet beds in
    /// layers"); 0, the default, relaxes every bed in one piece; 0 or [10, 1e6].
    double layer_height = 0.0;

    /// \throws InvalidInput naming the parameter, its value and the allowed range.
    void validate() const;
    /// \return min(D, L) in units of d_v (a ring's min(L, (D - DI) / 2), a spherocylinder's D).
    double smallest_dimension() const;
    /// \return the smallest and the largest of `scales` (1 and 1 where it is empty).
    std::pair<double, double> scale_range() const;
    /// \return pellet i's scale (1 where `scales` is empty).
    double scale(std::size_t i) const { return scales.empty() ? 1.0 : scales[i]; }
};

/// The state at the end of one stage: "settle" (the gravity held in the band until the mass
/// centre stops) or "final" (the gravity lowered until the depths are below tolerance).
struct PelletStage {
    std::string name;
    std::uint64_t steps = 0;
    double gravity = 0.0;       ///< the gravity parameter at its end (weight over stiffness)
    double max_depth = 0.0;     ///< the nodes' deepest penetration at its end, d_v
    double mass_centre_z = 0.0; ///< of the pellets that moved
    std::uint32_t layer = 0;    ///< in a bed in layers, the layer relaxed, from 0
};

/// A settled pellet bed.
struct PelletBed {
    /// Centroids (d_v), sizes (d_v / 2 each: the shape's unit) and orientations (the pellet's
    /// axis is its body z axis), in insertion order.
    Packing packing;
    std::vector<PelletStage> stages;
    std::uint64_t steps = 0;
    std::uint64_t neighbor_builds = 0;
    std::uint32_t layers = 1;     ///< the layers it was relaxed in (1: in one piece)
    std::size_t nodes = 0;        ///< nodes on each pellet's surface (0: a spherocylinder)
    double max_depth_nodes = 0.0; ///< the deepest node, pair or wall, d_v
    /// The exact penetration depths (the shape's pair_overlap and wall_overlap, the floor by
    /// the support function), d_v.
    double max_depth_pair = 0.0, max_depth_wall = 0.0;
    /// The largest force and torque over the bounding radius left on a pellet, in weights.
    double residual_force = 0.0, residual_torque = 0.0;
    /// The free pellets that overlap nothing at the end (no pellet, wall or floor by the exact
    /// depths): a bed at rest under gravity has none; many are a column still falling, which
    /// the settling took for still (a tall bed in one piece: docs/generate.md).
    std::size_t touching_nothing = 0;
    /// With friction: the pairs and the pellets at a wall whose friction the final stage let go
    /// (their overlap above tolerance held by it), and whether the rest kept it to the end.
    std::size_t sliding_pairs = 0, sliding_walls = 0;
    bool friction_kept = false;
    /// The taps the final stage gave a layer locked in a jam (docs/generate.md, "A floor layer
    /// squeezed flat"), all layers together.
    std::uint32_t kicks = 0;
};

/// \return the layers generate_pellet_bed relaxes a bed of `params` in, its pellets inserted
/// over `column` d_v: floor(column / layer_height) where the column exceeds twice the layer
/// height, else 1 (and 1 for a layer height of 0).
std::uint32_t pellet_layers(const PelletBedParameters& params, double column);

/// The column a bed of `params` is inserted over and the layers it is relaxed in.
struct PelletColumn {
    double height = 0.0;        ///< the top of the highest pellet's bounding sphere, d_v
    std::uint32_t layers = 1;   ///< pellet_layers(params, height)
    double largest_reach = 0.0; ///< the largest pellet's bounding radius, d_v
};
/// \return the column of `params` (the insertion, run on its own: as fast as a bed's start).
/// \throws InvalidInput for a parameter out of range
PelletColumn pellet_column(const PelletBedParameters& params);

/// The state of a pellet bed in layers after a whole layer: what a run needs to go on from
/// there and end with the same bits as one never stopped (checkpoint.hpp writes and reads it).
struct PelletCheckpoint {
    std::uint32_t layers_done = 0; ///< layers relaxed, from the bottom (empty ones counted)
    std::uint64_t steps = 0, neighbor_builds = 0; ///< so far, all layers
    double top = 0.0;     ///< the highest centroid of the relaxed layers, d_v
    bool on_floor = true; ///< no pellet relaxed yet: the next layer goes on the floor
    /// Every pellet in insertion order, d_v: those of the relaxed layers where they settled,
    /// the others where the insertion put them.
    std::vector<Vec3> centre;
    std::vector<Quaternion> turn;
    std::vector<PelletStage> stages; ///< so far
    std::size_t nodes = 0, sliding_pairs = 0, sliding_walls = 0;
    bool friction_kept = false;
    double residual_force = 0.0, residual_torque = 0.0; ///< the largest so far, weights
    std::uint32_t kicks = 0;                            ///< so far (PelletBed::kicks)
};

/// The hooks of a bed in layers (both optional).
struct PelletLayerHooks {
    /// Called after each layer with the state to save.
    std::function<void(const PelletCheckpoint&)> on_layer;
    /// Continue from this state (of the same parameters, its layers_done from 1 to the bed's
    /// layers) instead of from the first layer.
    const PelletCheckpoint* resume = nullptr;
};

/// Pour and settle a bed of pellets: insertion at random positions (uniform over the
/// container's cross-section, uniform in height over the column of void fraction e0) with
/// uniformly random orientations (Shoemake), then FIRE under gravity in two stages
/// (docs/pellets.md, "Generation"). Same seed and parameters, same bits, whatever the
/// number of threads.
/// \throws InvalidInput for a parameter out of range; ConvergenceError when max_steps pass;
/// Cancelled when control.should_stop says so.
/// \param layers with a bed in layers (pellet_column's layers above 1): its checkpoints
PelletBed generate_pellet_bed(const PelletBedParameters& params, const RunControl& control = {},
                              const PelletLayerHooks& layers = {});

/// The parameters that decide a pellet bed's bits, as JSON (all but max_steps, which only
/// bounds the run): what a checkpoint records and a resumed run must match. The shape by its
/// numbers, the container by its spec, the scales by their count and FNV-1a 64 hash.
nlohmann::json pellet_bed_parameters_json(const PelletBedParameters& params);

} // namespace packbed
