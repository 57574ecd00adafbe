# cmake -DFUZZER=exe -DCORPUS=dir -DWORK=dir -DRUNS=n -DMAX_LEN=bytes -P run_fuzzer.cmake
# One bounded libFuzzer run (fuzz/CMakeLists.txt): every file of the seed
# corpus first, then RUNS new inputs. New interesting inputs go to
# WORK/corpus (made afresh, so the repository's corpus is only read) and a
# crashing input to WORK/crash-<sha1>; a crash fails the test with the
# command that reproduces it and how to keep it as a regression input.
foreach(var FUZZER CORPUS WORK RUNS MAX_LEN)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_fuzzer.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/corpus)
# A fixed seed: the default run is the same run every time.
execute_process(COMMAND ${FUZZER} -runs=${RUNS} -max_len=${MAX_LEN} -seed=1 -timeout=10 -rss_limit_mb=2048
                        -print_final_stats=1 -artifact_prefix=${WORK}/ ${WORK}/corpus ${CORPUS}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(GLOB artifacts ${WORK}/crash-* ${WORK}/leak-* ${WORK}/timeout-* ${WORK}/oom-*)
  message(FATAL_ERROR "fuzzer failed (exit ${status}); input(s): ${artifacts}\n"
                      "reproduce: ${FUZZER} <input>\n"
                      "keep it: copy it to ${CORPUS}/regress-<what>, fix the fault (docs/fuzzing.md)")
endif()
