# Validates every shaders/*.glsl with glslangValidator (GLSL ES 300, no -V), and each variant the
# GLES backend compiles (same #defines as GlesCloth::variant_defines / output_program).
# Each is validated as the library embeds it, its #include lines spliced (into SPLICED_DIR).
# Inputs: VALIDATOR, SHADER_DIR, SPLICED_DIR.
include("${CMAKE_CURRENT_LIST_DIR}/../../plugin-native/src/backend/gles/splice_includes.cmake")
function(check file stage)
  file(READ "${SHADER_DIR}/${file}" text)
  drape_splice_includes("${SHADER_DIR}" "${text}" text)
  file(WRITE "${SPLICED_DIR}/${file}" "${text}")
  execute_process(COMMAND ${VALIDATOR} -l -S ${stage} ${ARGN} ${SPLICED_DIR}/${file}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(SEND_ERROR "glslangValidator ${file} ${ARGN}:\n${out}${err}")
  else()
    message(STATUS "ok: ${file} ${ARGN}")
  endif()
endfunction()

file(GLOB shaders RELATIVE ${SHADER_DIR} ${SHADER_DIR}/*.glsl)
foreach(f IN LISTS shaders)
  if(f MATCHES "\\.vert\\.glsl$")
    check(${f} vert)
  elseif(f MATCHES "\\.frag\\.glsl$")
    check(${f} frag)
  else()
    message(SEND_ERROR "${f}: name it <name>.vert.glsl or <name>.frag.glsl")
  endif()
endforeach()

# Simulation variants: pass x model x kinematic (+ the tether and interaction passes), grid (12 slots) and a mesh row of 32 slots.
foreach(slots 12 32)
  math(EXPR lambdas "(${slots} + 3) / 4")
  math(EXPR record "1 + ${lambdas}")
  foreach(kin "" "-DDRAPE_KINEMATIC")
    check(sim.vert.glsl vert -DDRAPE_PASS_MASS_SPRING -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1 ${kin})
    check(sim.vert.glsl vert -DDRAPE_PASS_PREDICT -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1 ${kin})
    check(sim.vert.glsl vert -DDRAPE_PASS_PREDICT -DDRAPE_DASHPOT -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1 ${kin})
    check(sim.vert.glsl vert -DDRAPE_PASS_PREDICT -DDRAPE_XPBD -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=${record}
          -DDRAPE_LAMBDA_VEC4=${lambdas} ${kin})
    check(sim.vert.glsl vert -DDRAPE_PASS_PREDICT -DDRAPE_IMPLICIT -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=3 ${kin})
  endforeach()
  check(sim.vert.glsl vert -DDRAPE_PASS_TETHER -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1)
  check(sim.vert.glsl vert -DDRAPE_PASS_MOVE -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1)
  check(sim.vert.glsl vert -DDRAPE_PASS_STILL -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1)
  foreach(interact "-DDRAPE_DRAG" "-DDRAPE_SHAPES=4" "-DDRAPE_DRAG;-DDRAPE_SHAPES=64")
    check(sim.vert.glsl vert -DDRAPE_PASS_INTERACT ${interact} -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1)
  endforeach()
  check(sim.vert.glsl vert -DDRAPE_PASS_TETHER -DDRAPE_XPBD -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=${record}
        -DDRAPE_LAMBDA_VEC4=${lambdas})
  foreach(commit "" "-DDRAPE_COMMIT")
    check(sim.vert.glsl vert -DDRAPE_PASS_CONSTRAINT -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=1 ${commit})
    check(sim.vert.glsl vert -DDRAPE_PASS_CONSTRAINT -DDRAPE_XPBD -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=${record}
          -DDRAPE_LAMBDA_VEC4=${lambdas} ${commit})
    check(sim.vert.glsl vert -DDRAPE_PASS_IMPLICIT -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=3 ${commit})
  endforeach()
  foreach(commit "" "-DDRAPE_COMMIT")
    check(sim.vert.glsl vert -DDRAPE_PASS_IMPLICIT -DDRAPE_PROLONG -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=3 ${commit})
  endforeach()
  foreach(kind RESTRICT DOWN SOLVE UP)
    check(sim.vert.glsl vert -DDRAPE_PASS_COARSE -DDRAPE_COARSE_${kind} -DDRAPE_SLOTS=${slots} -DDRAPE_RECORD=3)
  endforeach()
endforeach()
# Grab variants (gles_grab.cpp): the pick and the grab pass.
check(grab.vert.glsl vert -DDRAPE_PASS_PICK -DDRAPE_GRABS=16)
check(grab.vert.glsl vert -DDRAPE_PASS_GRAB -DDRAPE_GRABS=16)
# Self-collision (gles_self_collide.cpp): later hash layers, the collide pass for a mesh row of 32 slots.
check(self_hash.frag.glsl frag -DDRAPE_PEEL)
check(self_collide.vert.glsl vert -DDRAPE_SLOTS=32 -DDRAPE_SELF_LAYERS=8)
# Output variants: position only, normal only, both with copied-through bytes.
check(output.vert.glsl vert -DDRAPE_WRITE_POSITION)
check(output.vert.glsl vert -DDRAPE_WRITE_NORMAL)
check(output.vert.glsl vert -DDRAPE_WRITE_POSITION -DDRAPE_WRITE_NORMAL
      "-DDRAPE_KEEP_DECLS=in uint a_keep0\\; flat out uint v_keep0\\; in uvec3 a_keep1\\; flat out uvec3 v_keep1\\;"
      "-DDRAPE_KEEP_COPY=v_keep0 = a_keep0\\; v_keep1 = a_keep1\\;")
