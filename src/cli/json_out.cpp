#include "cli/json_out.h"

#include <fstream>
#include <stdexcept>

#include "base/util/atomic_file.h"

namespace zs {

void write_json_file(const std::string& path, const nlohmann::json& j) {
  AtomicFile out(path);
  {
    std::ofstream f(out.temp_path());
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error(path + ": cannot write stats");
  }
  out.commit();
}

}  // namespace zs
