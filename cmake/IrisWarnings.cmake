# iris_warnings(<target>): the project's warning set, applied PRIVATE to our own
# compiled code (never propagated to consumers). -Wconversion catches the float/double
# narrowing that spectral code is prone to; -Wshadow the m_/local mix-ups.
function(iris_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wconversion -Wshadow
      -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual -Wnull-dereference)
    if(IRIS_WERROR)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()

# iris_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...] [FIND ...]):
# a compiled module target iris_<name> (alias iris::<name>, exported as iris::<name>),
# headers under modules/<name>/include, installed with the package. FIND lists the
# find_dependency() lines a consumer of the installed package needs.
function(iris_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;FIND" ${ARGN})
  add_library(iris_${name} STATIC ${M_SOURCES})
  add_library(iris::${name} ALIAS iris_${name})
  set_target_properties(iris_${name} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(iris_${name} PUBLIC
    "$<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>"
    "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  target_link_libraries(iris_${name} PUBLIC iris::core ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  iris_warnings(iris_${name})
  if(IRIS_INSTALL)
    install(TARGETS iris_${name} EXPORT irisTargets)
    install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
  set_property(GLOBAL APPEND PROPERTY IRIS_BUILT_MODULES ${name})
  foreach(f IN LISTS M_FIND)
    set_property(GLOBAL APPEND PROPERTY IRIS_MODULE_FINDS "${f}")
  endforeach()
endfunction()
