// Checkpoint files of the fire solver's runs in layers: the state after a whole layer, from
// which a run resumes and ends with the same bits as one that was never stopped.
#pragma once

#include <filesystem>

#include "packbed/soft_sphere.hpp"

namespace packbed {

/// Write `checkpoint`, taken in a run with `parameters`, to `path`: under a temporary name in
/// the same folder, then renamed, so that `path` always holds a whole checkpoint.
/// Format: a line `packbed-checkpoint 2`; one line of JSON (the parameters, the counters, the
/// stage records, the sphere count and the FNV-1a 64 hash of the data); then the data: x, y,
/// z and r of every sphere in generation order, little-endian IEEE doubles.
/// \throws InvalidInput naming the file when it cannot be written
void write_checkpoint(const std::filesystem::path& path, const SoftSphereParameters& parameters,
                      const LayerCheckpoint& checkpoint);

/// Read a checkpoint written by write_checkpoint for a run with `parameters`.
/// \throws InvalidInput naming the file when it is not a checkpoint, is cut short or
/// corrupt, or was taken with other parameters (naming the first that differs;
/// max_iterations may differ)
LayerCheckpoint read_checkpoint(const std::filesystem::path& path,
                                const SoftSphereParameters& parameters);

} // namespace packbed
