# render --set POINTER=JSON:
# - the image equals, pixel for pixel, the render of the scene file edited
#   the same way (and differs from the unedited one); the EXR header records
#   the override; with several scenes each gets it;
# - each bad form exits 2 naming --set and the pointer, before anything is
#   traced or written;
# - --set with --shard and --state: the shards' states, moved to another
#   folder, merge there (the state carries the overridden scene) into the
#   pixels of one --set render; a --resume with the same --set goes on.
# cmake -DSPECTRACE=... -DCOMPARE=... -DSOURCE_DIR=... -DDIR=... -P cli_set_option.cmake
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${DIR})
file(MAKE_DIRECTORY ${DIR})
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)

# The scene files edited by hand (the text replaced), beside the original.
set(lamp ${SOURCE_DIR}/scenes/batch/lamp.json)  # a 2700 K lamp of 1 W
file(READ ${lamp} text)
string(REPLACE [["blackbody_k": 2700]] [["blackbody_k": 4000]] text_4000k "${text}")
string(REPLACE [["power_w": 1,]] [["power_w": 2,]] text_2w "${text}")
string(REPLACE [["power_w": 1,]] [["power_w": 2,]] text_2w_4000k "${text_4000k}")
foreach(edit 4000k 2w 2w_4000k)
  if(text_${edit} STREQUAL text)
    message(FATAL_ERROR "the edit ${edit} changed nothing in ${lamp}")
  endif()
  file(WRITE ${DIR}/lamp_${edit}.json "${text_${edit}}")
endforeach()
set(common --device cpu -q --no-png --beams 200000 --seed 5)
set(to_4000k --set /lights/0/spd/blackbody_k=4000)

run(${SPECTRACE} render ${lamp} ${to_4000k} ${common} -o ${DIR}/set.exr)
run(${SPECTRACE} render ${DIR}/lamp_4000k.json ${common} -o ${DIR}/edited.exr)
run(${SPECTRACE} render ${lamp} ${common} -o ${DIR}/plain.exr)
expect_same(${DIR}/set.exr ${DIR}/edited.exr)
execute_process(COMMAND ${COMPARE} ${DIR}/set.exr ${DIR}/plain.exr RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "--set changed nothing: set.exr has the pixels of the unedited scene")
endif()
file(STRINGS ${DIR}/set.exr overrides REGEX "blackbody_k")
if(NOT overrides MATCHES [[{"/lights/0/spd/blackbody_k":4000}]])
  message(FATAL_ERROR "set.exr's header does not record the override (found: '${overrides}')")
endif()

# Several scenes: each rendered with the override.
run(${SPECTRACE} render ${lamp} ${DIR}/lamp_2w.json ${to_4000k} ${common} -o ${DIR}/several/)
run(${SPECTRACE} render ${DIR}/lamp_2w_4000k.json ${common} -o ${DIR}/edited_2w.exr)
expect_same(${DIR}/several/lamp.exr ${DIR}/edited.exr)
expect_same(${DIR}/several/lamp_2w.exr ${DIR}/edited_2w.exr)

# Bad forms: "case|--set argument|regex of the message".
set(bad ${DIR}/bad)
set(cases
  [[no_equals|/lights/0/power_w|--set /lights/0/power_w: no '=' \(give POINTER=JSON]]
  [[no_slash|lights/0/power_w=2|--set lights/0/power_w=2: "lights/0/power_w" is not a JSON pointer \(it must start with '/']]
  [[empty_pointer|=2|--set =2: cannot replace the whole scene]]
  [[not_json|/observer=CIE1964_10|--set /observer=CIE1964_10: the value: /: invalid JSON: .*a string needs its quotes]]
  [[unknown_pointer|/lights/3/power_w=2|--set /lights/3/power_w=2: unknown pointer /lights/3/power_w: .*lamp.json has no /lights/3]]
  [[unknown_key|/lights/0/spd/blackbody=3000|--set /lights/0/spd/blackbody=3000: the scene with this override is invalid: .*lamp.json: /lights/0/spd(/blackbody)?: unknown key "blackbody"]]
  [[negative_kelvin|/lights/0/spd/blackbody_k=-3000|--set /lights/0/spd/blackbody_k=-3000: the scene with this override is invalid: .*lamp.json: /lights/0/spd/blackbody_k: ]])
foreach(case IN LISTS cases)
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 name)
  list(GET parts 1 argument)
  list(GET parts 2 regex)
  expect_refused(${name} "spectrace: error: ${regex}" ${SPECTRACE} render ${lamp} --set ${argument} ${common} -o ${bad}/x.exr)
endforeach()
expect_refused(repeated "--set /lights/0/power_w=3: /lights/0/power_w is already set by --set /lights/0/power_w=2"
  ${SPECTRACE} render ${lamp} --set /lights/0/power_w=2 --set /lights/0/power_w=3 ${common} -o ${bad}/x.exr)

if(EXISTS ${bad})
  message(FATAL_ERROR "a refused render created ${bad}")
endif()

# States: two shards with --set, merged elsewhere, give the one render's
# pixels; the state carries the overridden scene, which is in no file.
foreach(i 0 1)
  run(${SPECTRACE} render ${lamp} ${to_4000k} ${common} -o ${DIR}/shard${i}.exr --shard ${i}/2 --state ${DIR}/shard${i}.state)
endforeach()
file(MAKE_DIRECTORY ${DIR}/elsewhere)
file(RENAME ${DIR}/shard0.state ${DIR}/elsewhere/a.state)
file(RENAME ${DIR}/shard1.state ${DIR}/elsewhere/b.state)
execute_process(COMMAND ${SPECTRACE} merge a.state b.state -o merged.exr -q --no-png --state merged.state
                WORKING_DIRECTORY ${DIR}/elsewhere RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "merging --set shards failed (${rc}): ${err}")
endif()
expect_same(${DIR}/elsewhere/merged.exr ${DIR}/set.exr)
# A resume needs the same overrides: without them the scene differs.
expect_refused(resume_without_set "has changed since the state was written|differs"
  ${SPECTRACE} render ${lamp} ${common} -o ${DIR}/resumed.exr --resume ${DIR}/elsewhere/a.state)
message(STATUS "--set renders the edited scene, records it, refuses bad forms, and its shards merge anywhere")
