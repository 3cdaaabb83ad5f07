// write_vtu: TetMesh -> VTK XML unstructured grid (binary, appended), through
// vtk_tet_grid (the mesh as VTK's grid, also for VTK's filters).
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>

#include <cerrno>
#include <cstring>

#include "geometry/tets/io/vtk_capture.h"
#include "geometry/tets/io/vtk_io.h"
#include "geometry/tets/io/vtk_tet_grid.h"
#include "base/util/file_error.h"

namespace zs {

void write_vtu(const std::string& path, const TetMesh& m) {
  detail::VtkMessageCapture capture;
  const vtkSmartPointer<vtkUnstructuredGrid> grid = vtk_tet_grid(m, path);

  auto writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
  capture.watch(writer);
  writer->SetFileName(path.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary, not base64
  writer->SetCompressorTypeToNone();
  errno = 0;
  const int ok = writer->Write();
  const int write_errno = errno;
  if (!ok || capture.has_error()) {
    // The system's reason when there is one (a full disk): VTK's own
    // message is a dump of its pipeline request.
    std::string why = write_errno ? std::string(std::strerror(write_errno)) : capture.first_error();
    std::error_code ec;
    std::filesystem::remove(path, ec);  // never leave a partial file
    throw FileError(path, "cannot write VTU file" + (why.empty() ? std::string() : ": " + why));
  }
}

}  // namespace zs
