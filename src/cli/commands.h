// Each subcommand registers itself on its parent; main.cpp only wires them.
#pragma once

namespace CLI {
class App;
}

namespace zs {

void add_mesh_info_command(CLI::App& mesh);
void add_mesh_convert_command(CLI::App& mesh);
void add_mesh_generate_command(CLI::App& mesh);
void add_render_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_spheres_command(CLI::App& app);

}  // namespace zs
