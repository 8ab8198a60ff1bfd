# Debian splits OpenCV into per-module -dev packages (libopencv-core-dev, ...); only the
# libopencv-dev metapackage, which drags in Qt and VTK, ships OpenCVConfig.cmake. We install
# just the modules we use and make an imported target for each: OpenCV::<module>.
find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
foreach(module IN LISTS LFCAM_OPENCV_MODULES)
  find_library(OPENCV_${module}_LIBRARY NAMES opencv_${module} REQUIRED)
  add_library(OpenCV::${module} UNKNOWN IMPORTED)
  set_target_properties(OpenCV::${module} PROPERTIES
    IMPORTED_LOCATION "${OPENCV_${module}_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OPENCV_INCLUDE_DIR}")
  message(STATUS "OpenCV ${module}: ${OPENCV_${module}_LIBRARY}")
endforeach()
