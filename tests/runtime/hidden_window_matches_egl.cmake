# Renders the same frames through EGL and through a hidden GLFW window under
# xvfb-run and requires byte-identical PNG files.
file(MAKE_DIRECTORY ${WORK_DIR})
set(common --headless --scene cornell --size 160x90 --frames 2)
execute_process(COMMAND ${DEEPGI} ${common} --output ${WORK_DIR}/egl.png RESULT_VARIABLE egl_status)
if(NOT egl_status EQUAL 0)
  message(FATAL_ERROR "EGL render failed: ${egl_status}")
endif()
execute_process(COMMAND ${XVFB_RUN} -a ${DEEPGI} ${common} --hidden-window --output ${WORK_DIR}/glfw.png
                RESULT_VARIABLE glfw_status)
if(NOT glfw_status EQUAL 0)
  message(FATAL_ERROR "hidden GLFW window render failed: ${glfw_status}")
endif()
file(SHA256 ${WORK_DIR}/egl.png egl_hash)
file(SHA256 ${WORK_DIR}/glfw.png glfw_hash)
if(NOT egl_hash STREQUAL glfw_hash)
  message(FATAL_ERROR "hidden GLFW window image differs from the EGL image")
endif()
