file(REMOVE_RECURSE
  "libelan_base.a"
)
