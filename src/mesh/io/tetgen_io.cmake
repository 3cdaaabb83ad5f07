add_library(zsweep_tetgenio STATIC ${CMAKE_CURRENT_LIST_DIR}/tetgen_io.cpp)
target_link_libraries(zsweep_tetgenio PUBLIC zsweep_core PRIVATE tetgen::tetgen)
target_compile_options(zsweep_tetgenio PRIVATE ${ZS_WARN})
