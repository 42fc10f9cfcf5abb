# Finds every third-party library (see third_party_notes.md) and mends Debian 12's CMake quirks
# (../shared/PLATFORM.md) in one place, so the rest of the build sees clean imported targets.
find_package(embree 3 REQUIRED)
find_package(TBB REQUIRED)
find_package(OpenEXR 3 REQUIRED)  # EXR frames, read and written directly
find_package(PNG REQUIRED)        # PNG display images and textures
find_package(JPEG REQUIRED)       # JPEG textures (io/jpeg_texture.h)
# OpenImageIO: only in the run-time module libglint_oiio.so (film/oiio_module.h) and the tests.
find_package(OpenImageIO REQUIRED)
# Debian installs OpenColorIOConfig.cmake directly in /usr/share/cmake, outside the search path.
find_package(OpenColorIO REQUIRED HINTS /usr/share/cmake)
find_package(nlohmann_json 3.11 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(assimp REQUIRED)
find_package(Threads REQUIRED)
find_package(benchmark REQUIRED)  # glint bench

# Debian's OpenImageIO targets name /usr/include/opencv4 as an include directory even when
# OpenCV's headers are absent, and OpenColorIO's config, found outside its usual prefix, names
# "/include"; CMake then refuses to generate. Drop include paths that do not exist (the headers
# themselves are in /usr/include) rather than pulling in OpenCV.
foreach(target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util OpenColorIO::OpenColorIO)
  if(TARGET ${target})
    get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
    if(dirs)
      set(existing "")
      foreach(dir IN LISTS dirs)
        if(EXISTS "${dir}" OR dir MATCHES "^\\$<")
          list(APPEND existing "${dir}")
        endif()
      endforeach()
      set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${existing}")
    endif()
  endif()
endforeach()

if(GLINT_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)  # tools/check-layers.py
endif()
