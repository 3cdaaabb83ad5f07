# Sphere test sets C1-C4 (test_sets.h, pore_balls.h). C1, C3 and C4 are plain
# C++; C2 reads CGAL's demo image and needs VTK's distance transform, so it is
# a library of its own and VTK stays out of zsweep_spheres.
add_library(zsweep_spheregen STATIC ${CMAKE_CURRENT_LIST_DIR}/test_sets.cpp)
target_link_libraries(zsweep_spheregen PUBLIC zsweep_spheres)
target_compile_options(zsweep_spheregen PRIVATE ${ZS_WARN})

find_package(ZLIB REQUIRED)  # the .tar.gz the demo image comes in
add_library(zsweep_poreballs STATIC
  ${CMAKE_CURRENT_LIST_DIR}/demo_image.cpp   # tar.gz member, INRIMAGE-4
  ${CMAKE_CURRENT_LIST_DIR}/pore_balls.cpp)  # EDT + maximal balls (VTK)
target_link_libraries(zsweep_poreballs PUBLIC zsweep_spheres PRIVATE ZLIB::ZLIB
  VTK::CommonCore VTK::CommonDataModel VTK::ImagingCore VTK::ImagingGeneral)
target_compile_options(zsweep_poreballs PRIVATE ${ZS_WARN})
