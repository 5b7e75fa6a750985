file(REMOVE_RECURSE
  "libelan.a"
)
