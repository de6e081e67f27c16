# Layers held by the build. Every library sees the headers of its own source folders and, through
# CMake's PUBLIC/INTERFACE link dependencies, those of the libraries it links, and nothing else:
# there is no project-wide include root. An include of a header from a library that is not below
# (an upward include, e.g. vdrive/drive -> vdrive/firmware) fails to compile with "No such file".
#
# The headers stay where they are: for each library the build makes a folder of symbolic links,
# build/layers/<target>/<folder> -> <source>/<folder>, and puts that folder on the include path.

# vdrive_layer(<target> <folder>...): <target>'s headers are those under <folder>s (paths from
# the project root, as they are written in #include lines).
function(vdrive_layer target)
  set(root ${PROJECT_BINARY_DIR}/layers/${target})
  foreach(folder ${ARGN})
    set(link ${root}/${folder})
    get_filename_component(parent ${link} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(NOT IS_SYMLINK ${link})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${link} SYMBOLIC)
    endif()
  endforeach()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE ${root})
  elseif(type STREQUAL "EXECUTABLE")
    target_include_directories(${target} PRIVATE ${root})
  else()
    target_include_directories(${target} PUBLIC ${root})
  endif()
endfunction()

# vdrive_layer_library(<target> <folder> LINKS <libs>...): a static library of every .cpp under
# <folder>, whose headers are that folder's, linking <libs> PUBLIC (the layers below it).
function(vdrive_layer_library target folder)
  cmake_parse_arguments(ARG "" "" "LINKS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${folder}/*.cpp)
  add_library(${target} STATIC ${sources})
  vdrive_layer(${target} ${folder})
  target_link_libraries(${target} PUBLIC ${ARG_LINKS})
endfunction()
