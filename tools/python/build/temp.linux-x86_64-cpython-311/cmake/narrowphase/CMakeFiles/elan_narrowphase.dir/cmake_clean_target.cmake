file(REMOVE_RECURSE
  "libelan_narrowphase.a"
)
