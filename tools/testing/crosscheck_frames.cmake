# Sequences on the command line: `render --frames 3 --dump-records` writes one .hpsfv of three numbered frames;
# `replay` filters them through one table (the last frame's image equals render's, --frame-out writes each);
# `crosscheck` judges the file, and a scene traced with --frames, frame by frame with every policy; D7's eviction
# shader through --eviction-spv fails with exit 2 and a bundle of the three frames that reproduces it. A file with
# another number of frames than --frames, or --frame beside a file, exits 3.
include(${CMAKE_CURRENT_LIST_DIR}/bundle_reproduces.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/hpsf_run.cmake)
set(dir ${OUT}/crosscheck_frames)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
set(sequence ${dir}/sequence.hpsfv)

hpsf_run(0 render ${SCENE} --size 24x24 --spp 2 --frame 4 --frames 3 --capacity 4096 --eviction strict
    --temporal ema:0.5 --dump-records ${sequence} -o ${dir}/render.exr)
hpsf_run(0 replay ${sequence} --capacity 4096 --eviction strict --temporal ema:0.5 --frame-out ${dir}/replay-{frame}.exr
    -o ${dir}/replay.exr --json)
string(JSON frames LENGTH "${out}" frames)
string(JSON last GET "${out}" frames 2 frame)
if(NOT frames EQUAL 3 OR NOT last EQUAL 6)
  message(FATAL_ERROR "replay lists ${frames} frames, the last numbered ${last}")
endif()
foreach(frame 0004 0005 0006)
  if(NOT EXISTS ${dir}/replay-${frame}.exr)
    message(FATAL_ERROR "replay wrote no replay-${frame}.exr")
  endif()
endforeach()
execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/render.exr ${dir}/replay.exr RESULT_VARIABLE differ
                OUTPUT_VARIABLE report)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the replayed sequence's last frame differs from the rendered one:\n${report}")
endif()

foreach(policy none strict stale:2)
  hpsf_run(0 crosscheck ${sequence} --capacity 2048 --eviction ${policy} --temporal adaptive)
  if(NOT out MATCHES "frames: 3, each judged" OR NOT out MATCHES "compared over 3 frames")
    message(FATAL_ERROR "crosscheck of the file with ${policy}:\n${out}")
  endif()
endforeach()
hpsf_run(0 crosscheck ${SCENE} --size 16x16 --frames 2 --frame 1 --eviction strict --capacity 2048)
if(NOT out MATCHES "frames: 2, each judged")
  message(FATAL_ERROR "crosscheck of the scene over 2 frames:\n${out}")
endif()

hpsf_run(2 crosscheck ${sequence} --capacity 1024 --eviction strict --backends reference,vulkan
    --eviction-spv ${SHADER_VARIANTS}/eviction_D7.spv --repro-dir ${dir}/d7)
if(NOT out MATCHES "level 2 tables: FAIL" OR NOT out MATCHES "vulkan, frame 5: tombstone emptied before a live slot")
  message(FATAL_ERROR "D7's shader over the sequence:\n${out}")
endif()
hpsf_expect_bundle_reproduces(${dir}/d7)

# A team's own temporal blend that truncates the fixed64 blend: named at level 2, and its bundle reruns it.
hpsf_run(2 crosscheck ${sequence} --capacity 1024 --temporal ema:0.5 --backends reference,vulkan
    --temporal-spv ${SHADER_VARIANTS}/temporal_TRUNCATED_BLEND.spv --repro-dir ${dir}/truncated-blend)
if(NOT out MATCHES "level 2 tables: FAIL" OR NOT out MATCHES "vulkan, frame [0-9]+: blended cell differs from the temporal blend")
  message(FATAL_ERROR "a truncating temporal shader over the sequence:\n${out}")
endif()
hpsf_expect_bundle_reproduces(${dir}/truncated-blend)

hpsf_run(3 crosscheck ${sequence} --frames 2)
if(NOT err MATCHES "--frames: .*sequence.hpsfv holds 3 frames, not 2")
  message(FATAL_ERROR "--frames 2 of a 3-frame file: ${err}")
endif()
hpsf_run(3 crosscheck ${sequence} --frame 1)
if(NOT err MATCHES "--frame: .*carries its frames' numbers")
  message(FATAL_ERROR "--frame beside a file: ${err}")
endif()
hpsf_run(3 stats ${sequence})
if(NOT err MATCHES "holds 3 frames; this command filters one")
  message(FATAL_ERROR "stats of a sequence: ${err}")
endif()
