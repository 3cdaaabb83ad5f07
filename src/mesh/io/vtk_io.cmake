# zsweep_vtkio: the only library that includes VTK headers (all in .cpp files).
add_library(zsweep_vtkio STATIC
  ${CMAKE_CURRENT_LIST_DIR}/vtk_capture.cpp    # VTK error text -> FileError, not stderr
  ${CMAKE_CURRENT_LIST_DIR}/vtk_reader.cpp     # .vtu / legacy .vtk -> tets
  ${CMAKE_CURRENT_LIST_DIR}/vtk_scalar.cpp     # which array becomes the point scalar
  ${CMAKE_CURRENT_LIST_DIR}/vtu_writer.cpp     # tets -> .vtu
  ${CMAKE_CURRENT_LIST_DIR}/plot3d_reader.cpp  # PLOT3D -> 5-tet split, merged points
)
target_link_libraries(zsweep_vtkio PUBLIC zsweep_core PRIVATE
  VTK::CommonCore VTK::CommonDataModel VTK::CommonExecutionModel
  VTK::IOXML VTK::IOLegacy VTK::IOParallel VTK::FiltersCore VTK::FiltersGeneral)
target_compile_options(zsweep_vtkio PRIVATE ${ZS_WARN})
