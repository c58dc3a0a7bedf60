// Checkpoint files of the runs in layers (the fire solver's and the pellet beds'): the state after
// a whole layer, from which a run resumes and ends with the same bits as one that was never
// stopped.
#pragma once

#include <filesystem>
#include <istream>
#include <string_view>

#include "packbed/pellet_bed.hpp"
#include "packbed/soft_sphere.hpp"

namespace packbed {

/// Write `checkpoint`, taken in a run with `parameters`, to `path` whole or not at all
/// (replace_file: a temporary created exclusively beside it, then renamed).
/// Format: a line `packbed-checkpoint 3`; one line of JSON (the parameters, the counters, the
/// stage records, the sphere count); a line `fnv1a64 HEX`, the FNV-1a 64 hash of the JSON
/// line, a newline and the data; then the data: x, y, z and r of every sphere in generation
/// order, little-endian IEEE doubles, in units of Dp.
/// \throws InvalidInput naming the file when it cannot be written
void write_checkpoint(const std::filesystem::path& path, const SoftSphereParameters& parameters,
                      const LayerCheckpoint& checkpoint);

/// Read a checkpoint written by write_checkpoint for a run with `parameters`. The hash is a
/// check against accidents, not against forgery, so every field is also checked against what
/// this run can have produced (layers_done from 1 to fire_layers(parameters), 3 stages, counts
/// that add up, every sphere inside the container): a file edited by hand cannot crash or hang
/// the run.
/// \param name names the file in messages
/// \throws InvalidInput "--checkpoint NAME: ...; allowed: ..." when it is not a checkpoint,
/// is cut short, corrupt (naming the field) or was taken with other parameters (naming the
/// first that differs; max_iterations may differ)
LayerCheckpoint read_checkpoint(std::istream& input, std::string_view name,
                                const SoftSphereParameters& parameters);

/// Read the checkpoint file `path` (a regular file, see open_regular_file).
/// \throws InvalidInput as above
LayerCheckpoint read_checkpoint(const std::filesystem::path& path,
                                const SoftSphereParameters& parameters);

/// Write a pellet bed's `checkpoint`, taken in a run with `parameters`, to `path` whole or not
/// at all, as write_checkpoint does. Format: a line `packbed-pellet-checkpoint 1`; one line of
/// JSON (pellet_bed_parameters_json, the counters, the stage records, the pellet count); the
/// hash line as above; then x, y, z, qw, qx, qy and qz of every pellet in insertion order,
/// little-endian IEEE doubles, lengths in d_v.
/// \throws InvalidInput naming the file when it cannot be written
void write_pellet_checkpoint(const std::filesystem::path& path,
                             const PelletBedParameters& parameters,
                             const PelletCheckpoint& checkpoint);

/// Read a checkpoint written by write_pellet_checkpoint for a run with `parameters` whose
/// insertion gives `column` (pellet_column), every field checked against what that run can
/// have produced (layers_done from 1 to column.layers, stage records, each pellet near the
/// container and turned by a unit quaternion).
/// \throws InvalidInput as read_checkpoint (a sphere bed's checkpoint is refused as one)
PelletCheckpoint read_pellet_checkpoint(std::istream& input, std::string_view name,
                                        const PelletBedParameters& parameters,
                                        const PelletColumn& column);

/// Read the pellet checkpoint file `path` (a regular file, see open_regular_file).
/// \throws InvalidInput as above
PelletCheckpoint read_pellet_checkpoint(const std::filesystem::path& path,
                                        const PelletBedParameters& parameters,
                                        const PelletColumn& column);

} // namespace packbed
