// Temporaries of unfinished outputs are removed when a fatal signal ends the
// process (which still dies of that signal). Normal returns and exceptions
// unwind through AtomicFile's destructor (test_tile_writer.cpp).
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/util/atomic_file.h"
#include "base/util/temp_registry.h"
#include "support/test_paths.h"

namespace zs {
namespace {

namespace fs = std::filesystem;

TEST(TempRegistry, AtomicFileRegistersItsTemporaryUntilDone) {
  const fs::path dir = test::scratch_dir();
  const int before = registered_temp_files();
  {
    AtomicFile a((dir / "x.png").string());
    EXPECT_EQ(registered_temp_files(), before + 1);
    AtomicFile b((dir / "m.node").string());  // TetGen: .node and .ele too
    EXPECT_EQ(registered_temp_files(), before + 4);
    std::ofstream(a.temp_path()) << "x";
    a.commit();
    EXPECT_EQ(registered_temp_files(), before + 3);
  }
  EXPECT_EQ(registered_temp_files(), before);
  fs::remove_all(dir);
}

TEST(TempRegistry, FullTableDegradesToDestructorOnly) {
  std::vector<int> slots;
  for (int s; (s = register_temp_file("/nonexistent/x")) >= 0;) slots.push_back(s);
  EXPECT_GE(slots.size(), 32u);
  EXPECT_EQ(register_temp_file("/nonexistent/y"), -1);
  for (int s : slots) unregister_temp_file(s);
  EXPECT_EQ(register_temp_file(std::string(5000, 'a')), -1);  // too long: not registered
}

// In a child: handlers installed, a temporary written, then `sig` raised.
// Returns the child's wait status; the temporary must be gone.
int run_child(const fs::path& dir, int sig) {
  const std::string out = (dir / "big.exr").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    // What the process dies of, whatever a sanitizer build installed first
    // (ASan reports SIGSEGV itself and exits).
    std::signal(sig, SIG_DFL);
    install_temp_cleanup();
    AtomicFile f(out);
    std::ofstream(f.temp_path()) << "partial";
    ::raise(sig);
    ::_exit(0);  // not reached when the signal kills
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  size_t left = 0;
  for (const auto& e : fs::directory_iterator(dir)) ++left, ADD_FAILURE() << "left behind: " << e.path();
  EXPECT_EQ(left, 0u);
  return status;
}

TEST(TempRegistry, FatalSignalsRemoveTemporariesAndStillKill) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGSEGV, SIGABRT}) {
    SCOPED_TRACE(strsignal(sig));
    const fs::path dir = test::scratch_dir();
    const int status = run_child(dir, sig);
    EXPECT_TRUE(WIFSIGNALED(status));
    if (WIFSIGNALED(status)) EXPECT_EQ(WTERMSIG(status), sig);
    fs::remove_all(dir);
  }
}

}  // namespace
}  // namespace zs
