# The library is built as layers, one static library per folder of src/bounce, each linking only
# the layers below it. A layer's headers are reachable only through its own include root in the
# build tree, which holds a single link bounce/<layer> -> src/bounce/<layer>; a target therefore
# sees exactly the headers of the layers it links, and an include from a lower layer into a higher
# one fails to compile ("No such file") instead of quietly building a cycle.
set(BOUNCE_LAYER_ROOTS ${PROJECT_BINARY_DIR}/layers)

# bounce_layer(<name> [BELOW layers...] [SOURCES files...] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# Defines bounce_<name> (alias bounce::<name>, exported as bounce::<name>) from every .cpp under
# src/bounce/<name>, plus SOURCES; BELOW names the layers it builds on.
function(bounce_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "BELOW;SOURCES;PUBLIC_LIBS;PRIVATE_LIBS")
  set(folder ${PROJECT_SOURCE_DIR}/src/bounce/${name})
  set(root ${BOUNCE_LAYER_ROOTS}/${name})
  if(NOT IS_DIRECTORY ${folder})
    message(FATAL_ERROR "bounce_layer(${name}): ${folder} does not exist")
  endif()
  file(MAKE_DIRECTORY ${root}/bounce)
  file(CREATE_LINK ${folder} ${root}/bounce/${name} SYMBOLIC)

  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${folder}/*.cpp)
  set(target bounce_${name})
  add_library(${target} STATIC ${sources} ${arg_SOURCES})
  add_library(bounce::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${root}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE ${BOUNCE_WARNINGS} ${BOUNCE_ISA_FLAGS})
  list(TRANSFORM arg_BELOW PREPEND bounce_)
  target_link_libraries(${target}
    PUBLIC ${arg_BELOW} ${arg_PUBLIC_LIBS}
    PRIVATE ${arg_PRIVATE_LIBS})
  set_property(GLOBAL APPEND PROPERTY BOUNCE_LAYER_TARGETS ${target})
endfunction()

# Every folder of src/bounce must be a layer: a folder nobody declared would otherwise not be
# built at all, and its code would be missing without an error. gpu/ is the exception: the CUDA
# backend, built by its own CMakeLists.txt on top of every layer when nvcc is found.
function(bounce_check_every_folder_is_a_layer)
  get_property(targets GLOBAL PROPERTY BOUNCE_LAYER_TARGETS)
  file(GLOB folders LIST_DIRECTORIES true CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/bounce/*)
  foreach(folder IN LISTS folders)
    get_filename_component(name ${folder} NAME)
    if(IS_DIRECTORY ${folder} AND NOT name STREQUAL "gpu" AND NOT bounce_${name} IN_LIST targets)
      message(FATAL_ERROR "src/bounce/${name} is not a layer: add bounce_layer(${name} BELOW ...) "
        "to src/CMakeLists.txt")
    endif()
  endforeach()
endfunction()
