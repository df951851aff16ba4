# OpenCV::quality: SSIM from OpenCV's quality module (libopencv-contrib-dev). Debian ships OpenCV's CMake config
# only in the libopencv-dev metapackage, which pulls in every module; the three libraries hpsf needs are found
# directly. Used by hpsf's own build and by hpsfConfig.cmake for the reports component.
if(NOT TARGET OpenCV::quality)
  find_path(OPENCV_INCLUDE_DIR opencv2/quality/qualityssim.hpp PATH_SUFFIXES opencv4)
  find_library(OPENCV_CORE_LIBRARY opencv_core)
  find_library(OPENCV_IMGPROC_LIBRARY opencv_imgproc)
  find_library(OPENCV_QUALITY_LIBRARY opencv_quality)
  include(FindPackageHandleStandardArgs)
  find_package_handle_standard_args(OpenCVQuality
    REQUIRED_VARS OPENCV_INCLUDE_DIR OPENCV_QUALITY_LIBRARY OPENCV_IMGPROC_LIBRARY OPENCV_CORE_LIBRARY)
  if(OpenCVQuality_FOUND)
    add_library(OpenCV::quality INTERFACE IMPORTED)
    target_include_directories(OpenCV::quality SYSTEM INTERFACE ${OPENCV_INCLUDE_DIR})
    target_link_libraries(OpenCV::quality
      INTERFACE ${OPENCV_QUALITY_LIBRARY} ${OPENCV_IMGPROC_LIBRARY} ${OPENCV_CORE_LIBRARY})
  endif()
endif()
