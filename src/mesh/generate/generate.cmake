# zsweep_generate: mesh generation (TetGen, CGAL Mesh_3) and scalar fields.
# CGAL Mesh_3 lives in cgal_mesher.cpp alone so it is compiled once.
find_package(CGAL REQUIRED COMPONENTS ImageIO)
set(ZS_GEN_DIR ${CMAKE_CURRENT_LIST_DIR})
add_library(zsweep_generate STATIC
  ${ZS_GEN_DIR}/tet_ops.cpp
  ${ZS_GEN_DIR}/shapes.cpp
  ${ZS_GEN_DIR}/shape_mesher.cpp
  ${ZS_GEN_DIR}/tetgen_mesher.cpp
  ${ZS_GEN_DIR}/surface_io.cpp
  ${ZS_GEN_DIR}/surface_precheck.cpp
  ${ZS_GEN_DIR}/implicit_shapes.cpp
  ${ZS_GEN_DIR}/cgal_mesher.cpp
  ${ZS_GEN_DIR}/voxel_image.cpp
  ${ZS_GEN_DIR}/iso_region.cpp
  ${ZS_GEN_DIR}/scalar_fields.cpp
  ${ZS_GEN_DIR}/distance_field.cpp
)
target_link_libraries(zsweep_generate PUBLIC zsweep_core PRIVATE tetgen::tetgen CGAL::CGAL CGAL::CGAL_ImageIO)
target_compile_options(zsweep_generate PRIVATE ${ZS_WARN})
