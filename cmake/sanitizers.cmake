# MPILE_SANITIZE=address: AddressSanitizer + UndefinedBehaviorSanitizer; =thread: ThreadSanitizer.
if(MPILE_SANITIZE STREQUAL "address")
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
elseif(MPILE_SANITIZE STREQUAL "thread")
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
elseif(NOT MPILE_SANITIZE STREQUAL "")
  message(FATAL_ERROR "MPILE_SANITIZE must be empty, 'address' or 'thread', not '${MPILE_SANITIZE}'")
endif()
