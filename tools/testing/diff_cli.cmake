# hpsf diff's exit codes and its WARN rule on constructed EXRs (oiiotool makes them): 0 for the same image, 1 for
# one pixel off by 0.1 between --warn 0.05 and --fail 0.2 (where idiff prints PASS), 2 above --fail and with the
# default thresholds; 3 for bad input (a missing file, a PNG, another size, other channels, a metric without
# its threshold, a --warn on the wrong side of --fail, for lower- and higher-is-better metrics), with no heatmap
# left behind.
set(dir ${OUT}/diff_cli)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
function(make_image)
  execute_process(COMMAND oiiotool ${ARGN} RESULT_VARIABLE code ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "oiiotool ${ARGN} failed: ${err}")
  endif()
endfunction()
make_image(--pattern constant:color=0.5,0.25,0.125 8x8 3 -d float -o ${dir}/base.exr)
make_image(${dir}/base.exr --box:color=0.6,0.25,0.125:fill=1 3,4,3,4 -o ${dir}/one_pixel.exr)
make_image(--pattern constant:color=0.5,0.25,0.125 8x6 3 -d float -o ${dir}/smaller.exr)
make_image(--pattern constant:color=0.5,0.25,0.125,1 8x8 4 -d float -o ${dir}/rgba.exr)
make_image(${dir}/base.exr -o ${dir}/base.png)

# expect(CODE REGEX ARGS...): hpsf diff ARGS exits CODE, prints REGEX; a bad input (3) writes no heatmap.
function(expect code regex)
  file(REMOVE ${dir}/heat.png)
  execute_process(COMMAND ${HPSF} diff ${ARGN} --heatmap ${dir}/heat.png RESULT_VARIABLE got OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  message("hpsf diff ${ARGN}: exit ${got}\n${out}${err}")
  if(NOT got EQUAL code)
    message(FATAL_ERROR "hpsf diff ${ARGN}: exit ${got}, expected ${code}")
  endif()
  if(NOT "${out}${err}" MATCHES "${regex}")
    message(FATAL_ERROR "hpsf diff ${ARGN}: the output does not match '${regex}'")
  endif()
  if(code EQUAL 3 AND EXISTS ${dir}/heat.png)
    message(FATAL_ERROR "hpsf diff ${ARGN}: bad input left a heatmap behind")
  endif()
  if(NOT code EQUAL 3 AND NOT EXISTS ${dir}/heat.png)
    message(FATAL_ERROR "hpsf diff ${ARGN}: no heatmap written")
  endif()
endfunction()

expect(0 "PASS: max 0 is not above --warn 0" ${dir}/base.exr ${dir}/base.exr)
expect(1 "WARN: max 0.1 at \\(3, 4, R\\) is above --warn 0.05, not above --fail 0.2" ${dir}/one_pixel.exr ${dir}/base.exr --warn 0.05 --fail 0.2)
expect(1 "\"verdict\": \"WARN\"" ${dir}/one_pixel.exr ${dir}/base.exr --warn 0.05 --fail 0.2 --json)
expect(2 "FAIL: max 0.1 at \\(3, 4, R\\) is above --fail 0.05" ${dir}/one_pixel.exr ${dir}/base.exr --fail 0.05)
expect(2 "FAIL: max 0.1 at \\(3, 4, R\\) is above --fail 1e-06" ${dir}/one_pixel.exr ${dir}/base.exr)
expect(0 "PASS: psnr" ${dir}/one_pixel.exr ${dir}/base.exr --metric psnr --fail 40)
expect(2 "FAIL: psnr 42.8.* is below --fail 50" ${dir}/one_pixel.exr ${dir}/base.exr --metric psnr --fail 50)
expect(3 "--fail: give the threshold for --metric psnr" ${dir}/one_pixel.exr ${dir}/base.exr --metric psnr)
expect(3 "--warn: must not be above --fail" ${dir}/one_pixel.exr ${dir}/base.exr --warn 0.3 --fail 0.2)
# psnr and ssim are better when higher: their --warn lies above --fail, a psnr between the two warns, and one
# below --fail fails (each direction once, so a rule written for "worse is greater" alone cannot pass).
expect(3 "--warn: must not be below --fail" ${dir}/one_pixel.exr ${dir}/base.exr --metric psnr --warn 30 --fail 40)
expect(3 "--warn: must not be below --fail" ${dir}/one_pixel.exr ${dir}/base.exr --metric ssim --warn 0.5 --fail 0.9)
expect(1 "WARN: psnr 42.8.* is below --warn 50, not below --fail 40" ${dir}/one_pixel.exr ${dir}/base.exr --metric psnr --warn 50 --fail 40)
expect(1 "WARN: ssim .* is below --warn 0.9999" ${dir}/one_pixel.exr ${dir}/base.exr --metric ssim --warn 0.9999 --fail 0.5)
expect(2 "FAIL: ssim .* is below --fail 0.9999" ${dir}/one_pixel.exr ${dir}/base.exr --metric ssim --fail 0.9999)
expect(3 "missing.exr: no such image file" ${dir}/missing.exr ${dir}/base.exr)
expect(3 "base.png: not an OpenEXR image" ${dir}/base.png ${dir}/base.exr)
expect(3 "base.exr is 8x8 \\[R,G,B\\], .*smaller.exr is 8x6 \\[R,G,B\\]" ${dir}/base.exr ${dir}/smaller.exr)
expect(3 "rgba.exr is 8x8 \\[R,G,B,A\\]" ${dir}/base.exr ${dir}/rgba.exr)

# What idiff says on the WARN case: PASS, the reason hpsf has its own rule.
execute_process(COMMAND idiff -warn 0.05 -fail 0.2 ${dir}/one_pixel.exr ${dir}/base.exr RESULT_VARIABLE code OUTPUT_VARIABLE out)
message("idiff -warn 0.05 -fail 0.2: exit ${code}\n${out}")
