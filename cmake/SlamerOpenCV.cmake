# Finds the OpenCV modules we use and defines slamer::opencv (an INTERFACE
# target linking them). Debian's narrow libopencv-<module>-dev packages ship
# headers and libraries but no OpenCVConfig.cmake (only the all-modules
# libopencv-dev has it), so we try the config package first and otherwise
# look for each module's library ourselves.
set(SLAMER_OPENCV_MODULES core imgproc imgcodecs)

add_library(slamer_opencv INTERFACE)
find_package(OpenCV QUIET COMPONENTS ${SLAMER_OPENCV_MODULES})
if(OpenCV_FOUND)
  target_include_directories(slamer_opencv SYSTEM INTERFACE ${OpenCV_INCLUDE_DIRS})
  target_link_libraries(slamer_opencv INTERFACE ${OpenCV_LIBS})
  message(STATUS "OpenCV ${OpenCV_VERSION} (config package)")
else()
  find_path(SLAMER_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
  if(NOT SLAMER_OPENCV_INCLUDE_DIR)
    message(FATAL_ERROR "OpenCV headers not found: apt-get install libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev")
  endif()
  target_include_directories(slamer_opencv SYSTEM INTERFACE ${SLAMER_OPENCV_INCLUDE_DIR})
  foreach(module ${SLAMER_OPENCV_MODULES})
    find_library(SLAMER_OPENCV_${module}_LIBRARY opencv_${module})
    if(NOT SLAMER_OPENCV_${module}_LIBRARY)
      message(FATAL_ERROR "OpenCV module ${module} not found: apt-get install libopencv-${module}-dev")
    endif()
    target_link_libraries(slamer_opencv INTERFACE ${SLAMER_OPENCV_${module}_LIBRARY})
  endforeach()
  message(STATUS "OpenCV modules ${SLAMER_OPENCV_MODULES} in ${SLAMER_OPENCV_INCLUDE_DIR}")
endif()
