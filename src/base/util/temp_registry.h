// The temporary files this process has open under AtomicFile, so that a
// fatal signal, which skips the destructors, still removes them.
//
// A fixed table of slots, filled and emptied with atomics: the signal
// handler walks it with only async-signal-safe calls (unlink), never
// allocating or locking. A file registered while every slot is taken is
// still removed by its destructor, only not on a signal.
#pragma once

#include <string>

namespace zs {

// Registers `path` for removal on a fatal signal; returns the slot
// (or -1 when the table is full or the path too long).
int register_temp_file(const std::string& path);
// Drops the slot (after the file was renamed into place or removed).
void unregister_temp_file(int slot);

// Installs handlers for SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ
// and the crash signals (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT): each
// removes every registered file, then dies of the same signal (the exit
// status still says which). For the command
// line program only: a host process (Python) keeps its own handlers.
// SIGKILL cannot be caught: its temporaries stay, named NAME.zs-tmp-PID-N.EXT.
void install_temp_cleanup();

// For tests: the number of registered files.
int registered_temp_files();

}  // namespace zs
