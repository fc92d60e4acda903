# MPILE_SANITIZE=address: AddressSanitizer + UndefinedBehaviorSanitizer; =thread: ThreadSanitizer.
if(MPILE_SANITIZE STREQUAL "address")
  # UBSan's default set less the checks that instrument every load and store (alignment, null,
  # object-size), every pointer step (pointer-overflow) and every virtual call (vptr):
  # AddressSanitizer already stops at an out-of-bounds or null access, and these five were half of
  # the build (the solver's largest batch 53 s with them, 29 s without). float-cast-overflow, not in the default set, is added: a
  # NaN or huge coordinate cast to a cell index is undefined behaviour the rest does not catch.
  set(mpile_ubsan undefined,float-cast-overflow)
  add_compile_options(-fsanitize=address,${mpile_ubsan}
                      -fno-sanitize=alignment,null,object-size,pointer-overflow,vptr
                      -fno-sanitize-recover=${mpile_ubsan} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,${mpile_ubsan})
elseif(MPILE_SANITIZE STREQUAL "thread")
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
elseif(NOT MPILE_SANITIZE STREQUAL "")
  message(FATAL_ERROR "MPILE_SANITIZE must be empty, 'address' or 'thread', not '${MPILE_SANITIZE}'")
endif()
