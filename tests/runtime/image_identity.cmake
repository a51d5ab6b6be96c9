# Renders every built-in scene with every generator at 320x180, 3 frames, and
# requires the final PNG and every --dump PFM to hash to the values recorded in
# image_identity_hashes.txt. Those hashes were taken from the renderer before
# its passes were restructured, so this checks that a refactor leaves every
# pixel of every pass output unchanged. A change meant to alter pixels updates
# the file in the same commit and says so. They were taken with the
# solid-angle estimator, then the default, which the runs name explicitly.
#
# Arguments: -DDEEPGI=<executable> -DHASHES=<file> -DWORK_DIR=<scratch folder>
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(STRINGS ${HASHES} expected_lines REGEX "^[0-9a-f]+ ")
set(actual_lines)
foreach(scene cornell atrium warehouse)
  foreach(generator peel previous reproject)
    set(run ${scene}-${generator})
    set(dump ${WORK_DIR}/${run})
    execute_process(
      COMMAND ${DEEPGI} --headless --scene ${scene} --generator ${generator} --ao-method solid-angle --size 320x180
              --frames 3 --output ${WORK_DIR}/${run}.png --dump ${dump}
      RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "deepgi failed for ${run}: ${status}")
    endif()
    file(SHA256 ${WORK_DIR}/${run}.png hash)
    list(APPEND actual_lines "${hash} ${run}/final.png")
    file(GLOB outputs RELATIVE ${dump} ${dump}/*.pfm)
    list(SORT outputs)
    foreach(output ${outputs})
      file(SHA256 ${dump}/${output} hash)
      list(APPEND actual_lines "${hash} ${run}/${output}")
    endforeach()
  endforeach()
endforeach()

list(SORT expected_lines)
list(SORT actual_lines)
# The measured hashes, always written, so that a change meant to alter pixels
# re-records by keeping the header of image_identity_hashes.txt and replacing
# its hash lines with this file's.
string(REPLACE ";" "\n" actual_text "${actual_lines}")
file(WRITE ${WORK_DIR}/actual_hashes.txt "${actual_text}\n")
set(failures 0)
foreach(line ${actual_lines})
  list(FIND expected_lines "${line}" found)
  if(found EQUAL -1)
    message(SEND_ERROR "not in the recorded hashes: ${line}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
foreach(line ${expected_lines})
  list(FIND actual_lines "${line}" found)
  if(found EQUAL -1)
    message(SEND_ERROR "recorded but not produced: ${line}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} image hash mismatches (scratch output in ${WORK_DIR})")
endif()
list(LENGTH actual_lines count)
message(STATUS "${count} images match their recorded hashes")
