// Internal to the VTK file code (built in zsweep_geometry_tets_io; the surface
// reader in geometry/triangles/io/ uses it too): routes VTK's error/warning
// text away from stderr so failures surface as one-line FileErrors. No VTK headers here on purpose.
#pragma once

#include <memory>
#include <string>

class vtkObject;

namespace zs::detail {

// While alive, every VTK error/warning message (from any object) is captured
// instead of printed. Not thread-safe: VTK's output window is process-global.
class VtkMessageCapture {
 public:
  VtkMessageCapture();
  ~VtkMessageCapture();
  VtkMessageCapture(const VtkMessageCapture&) = delete;
  VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

  // Also observe ErrorEvent on obj: writers report some failures only there.
  void watch(vtkObject* obj);

  bool has_error() const;
  // First error as one line without VTK's "file, line / Class (0x..):"
  // prefix; "" if none.
  std::string first_error() const;
  // First warning, same form; "" if none. Readers warn about data that does
  // not match its declaration (e.g. a truncated legacy file).
  std::string first_warning() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace zs::detail
