// read_pellet_checkpoint on a stream, for the parameters the seed checkpoints were taken with
// (`packbed generate --shape spherocylinder:1,1 -a 3 -n 100 --layer-height 10`, seed 1: five
// layers): a checkpoint that a run can resume from, or InvalidInput. Each input is read as it
// is and re-signed (fuzz::resigned), as fuzz_checkpoint does.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "packbed/checkpoint.hpp"

namespace {

packbed::PelletBedParameters seed_parameters() {
    packbed::PelletBedParameters p;
    p.shape = packbed::SpherocylinderShape::of_aspect(1.0);
    p.container = packbed::Container::tube(3);
    p.particles = 100;
    p.layer_height = 10;
    return p;
}

const packbed::PelletBedParameters parameters = seed_parameters();
const packbed::PelletColumn column = packbed::pellet_column(parameters);

/// What a run resumes from: every pellet, finite, turned by a unit quaternion; a layer count
/// within the run's; stage records of the layers done, finite.
void check(const packbed::PelletCheckpoint& c) {
    using packbed::fuzz::finding;
    if (c.centre.size() != parameters.particles || c.turn.size() != parameters.particles)
        finding("read_pellet_checkpoint returned " + std::to_string(c.centre.size()) +
                " pellets for a run of " + std::to_string(parameters.particles));
    for (std::size_t i = 0; i < c.centre.size(); ++i) {
        const auto& p = c.centre[i];
        const auto& q = c.turn[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            finding("read_pellet_checkpoint returned pellet " + std::to_string(i) + " not finite");
        if (!(std::abs(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z - 1.0) <= 1e-9))
            finding("read_pellet_checkpoint returned pellet " + std::to_string(i) +
                    " turned by no unit quaternion");
    }
    if (c.layers_done < 1 || c.layers_done > column.layers)
        finding("read_pellet_checkpoint returned layers_done = " + std::to_string(c.layers_done) +
                " for a run of " + std::to_string(column.layers) + " layers");
    if (!std::isfinite(c.top) || !std::isfinite(c.residual_force) ||
        !std::isfinite(c.residual_torque))
        finding("read_pellet_checkpoint returned a top or residual that is not finite");
    if (c.stages.size() > 2 * std::size_t{c.layers_done})
        finding("read_pellet_checkpoint returned more than two stage records a layer");
    for (const auto& s : c.stages) {
        if (!std::isfinite(s.gravity) || !std::isfinite(s.max_depth) ||
            !std::isfinite(s.mass_centre_z))
            finding("read_pellet_checkpoint returned a stage record that is not finite");
        if (s.layer >= c.layers_done)
            finding("read_pellet_checkpoint returned a stage of a layer not done");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    packbed::fuzz::read_as_is_and_resigned(data, size, [](std::istream& input) {
        check(packbed::read_pellet_checkpoint(input, "fuzz.checkpoint", parameters, column));
    });
    return 0;
}
