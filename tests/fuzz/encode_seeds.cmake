# Encodes text-format seeds into the binary corpus of one RPC fuzzer:
#   cmake -DPROTOC=... -DPROTO_DIR=... -DTYPE=freeform.v1.X -DOUT_DIR=...
#         -DSTAMP=... -DSEED_DIR=... -P encode_seeds.cmake
# Each SEED_DIR/<name>.textproto becomes OUT_DIR/<name>; a seed protoc
# cannot parse fails the build.
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})
file(GLOB protos ${PROTO_DIR}/freeform/v1/*.proto)
file(GLOB seeds ${SEED_DIR}/*.textproto)
foreach(seed IN LISTS seeds)
  get_filename_component(name ${seed} NAME_WE)
  execute_process(
    COMMAND ${PROTOC} --encode=${TYPE} -I ${PROTO_DIR} ${protos}
    INPUT_FILE ${seed}
    OUTPUT_FILE ${OUT_DIR}/${name}
    ERROR_VARIABLE error
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${seed} is not a valid ${TYPE}:\n${error}")
  endif()
endforeach()
file(TOUCH ${STAMP})
