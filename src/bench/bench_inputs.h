// What the benchmarks take and write, checked before any work: their inputs
// (both measure the tet-mesh renderer, so sphere and surface inputs are
// refused, not measured as empty images), the names their rows carry, and
// their output paths.
#pragma once

#include <string>
#include <vector>

namespace zs {

// Throws FileError naming the first input that is missing or is not a tet
// mesh or volume scene ("cow.off: a surface mesh; bench scan measures tet
// meshes (volume scenes)"). `bench` names the command in the message;
// "default" (the embedded scene) is accepted when allow_default is set.
void check_volume_inputs(const std::vector<std::string>& inputs, const std::string& bench, bool allow_default);

// One row name per input, all distinct: the file's stem ("spx"), or where
// two inputs share a stem their file names ("spx.json", "spx.off"), and where
// those agree too a numbered suffix on the later ones ("spx.off-2"). Commas
// and path separators become '_' (the names go into CSV cells and file names).
std::vector<std::string> bench_row_names(const std::vector<std::string>& inputs);

// Fails (FileError) unless `csv` (if not empty) can be written and `plots_dir` (if not
// empty) is a directory that exists or can be created and written; creates
// nothing.
void check_bench_outputs(const std::string& csv, const std::string& plots_dir);

}  // namespace zs
