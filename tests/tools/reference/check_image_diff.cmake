# image_diff's verdicts and errors, on the documentation's aapoly images
# (Method 1 and Method 3 composited over black; docs/rasterizer.md quotes
# 3828 pixels differing, max 40): within bounds passes (0), outside fails
# (1), and a missing, undecodable or differently sized image is an error (2)
# that names the file, never a pass. Run with -DIMAGE_DIFF=... -DIMAGES=docs/images
# -DWORK_DIR=<scratch folder>.
function(expect_image_diff status pattern)
  execute_process(COMMAND ${IMAGE_DIFF} ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE result)
  if(NOT result STREQUAL status)
    message(FATAL_ERROR "image_diff ${ARGN}: status ${result}, expected ${status}\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${pattern}")
    message(FATAL_ERROR "image_diff ${ARGN}: output lacks '${pattern}':\n${out}${err}")
  endif()
endfunction()

set(method1 ${IMAGES}/aapoly_method1.png)
set(method3 ${IMAGES}/aapoly_method3.png)
expect_image_diff(0 "320x240: 3828 of 76800 pixels differ \\(4.98%\\), max difference 40, mean 0.301"
                  ${method1} ${method3} --min-differing 1000)
expect_image_diff(1 "3828 pixels differ, fewer than the 4000 required" ${method1} ${method3} --min-differing 4000)
expect_image_diff(1 "more than the 0 allowed" ${method1} ${method3} --max-differing 0)
expect_image_diff(0 "0 of 76800 pixels differ" ${method3} ${method3} --max-differing 0)
expect_image_diff(1 "fewer than the 1 required" ${method3} ${method3} --min-differing 1)

file(MAKE_DIRECTORY ${WORK_DIR})
expect_image_diff(2 "cannot read ${WORK_DIR}/missing.png" ${method1} ${WORK_DIR}/missing.png --min-differing 0)
file(WRITE ${WORK_DIR}/not_an_image.png "not a PNG\n")
expect_image_diff(2 "cannot read ${WORK_DIR}/not_an_image.png" ${WORK_DIR}/not_an_image.png ${method1})
expect_image_diff(2 "the first image is 320x240, the second 240x160" ${method1} ${IMAGES}/aapoly_method1_crop4x.png)
message(STATUS "image_diff: verdicts and errors as documented")
