# ccache where present (TESSERA_CCACHE, on by default): a rebuild of an
# unchanged translation unit, in this tree or in another clone or work tree
# of the project on the same machine, is a cache hit. base_dir is the source
# tree, so the paths in a compile command (sources and the build folder
# inside the tree) are made relative and two clones share one cache;
# hash_dir off lets them share it although their folders differ (the price:
# the debug information of a hit names the folder of the compile that filled
# the cache). Without ccache nothing changes: the compilers run directly.
option(TESSERA_CCACHE "Compile through ccache when it is installed" ON)
if(TESSERA_CCACHE)
  find_program(TESSERA_CCACHE_PROGRAM ccache)
  if(TESSERA_CCACHE_PROGRAM)
    set(launcher ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR} CCACHE_NOHASHDIR=1
                 CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
                 ${TESSERA_CCACHE_PROGRAM})
    set(CMAKE_C_COMPILER_LAUNCHER ${launcher})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${launcher})
  endif()
endif()
