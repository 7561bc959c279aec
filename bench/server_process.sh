# Sourced by the benchmark scripts that start `hexlod serve`: a scratch folder `$work` and
# `$server_pid`, both cleaned up on exit however the script ends, so a failed run leaves no
# server holding its port.
work=$(mktemp -d)
server_pid=
cleanup() {
    [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT
