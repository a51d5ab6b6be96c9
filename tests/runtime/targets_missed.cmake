# The "targets missed" entries (docs/architecture.md, "How tests are named"):
# every target an accuracy suite measures, target beside measured, printed
# from the table the suite wrote (print_targets.sh) by an entry of its own
# that needs the suite's run and reports itself skipped while any target is
# missed, so every ctest summary names the misses.
#
# deepgi_add_targets_missed(NAME <entry> TITLE <printed title> TABLE <table.md>
#                           SUITE <the suite's test> LABELS <label>...)
#
# The suite (defined before the call) sets up a fixture named after the
# entry, which the entry requires: ctest runs the suite first, and a run of
# the entry alone runs the suite too.
#
# Each call also adds "<title>:<table>" to the global property
# DEEPGI_TARGETS_MISSED; deepgi_write_targets_missed_list() writes them to
# targets-missed.list beside the tables, which scripts/test.sh reads to print
# the misses again at the end of its log, so the list lives here only.
function(deepgi_add_targets_missed)
  cmake_parse_arguments(PARSE_ARGV 0 ARG "" "NAME;TITLE;TABLE;SUITE" "LABELS")
  add_test(NAME ${ARG_NAME}
    COMMAND sh ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/print_targets.sh "${ARG_TITLE}" ${ARG_TABLE})
  set_property(TEST ${ARG_SUITE} APPEND PROPERTY FIXTURES_SETUP ${ARG_NAME})
  set_tests_properties(${ARG_NAME} PROPERTIES LABELS "${ARG_LABELS}"
    FIXTURES_REQUIRED ${ARG_NAME} SKIP_RETURN_CODE 77)
  set_property(GLOBAL APPEND PROPERTY DEEPGI_TARGETS_MISSED "${ARG_TITLE}:${ARG_TABLE}")
endfunction()

function(deepgi_write_targets_missed_list)
  get_property(entries GLOBAL PROPERTY DEEPGI_TARGETS_MISSED)
  list(JOIN entries "\n" text)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/targets-missed.list "${text}\n")
endfunction()
