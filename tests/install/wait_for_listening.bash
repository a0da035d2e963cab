# Sourced by the install tests (which define fail): waits for a started `vots serve` to print its URL.
wait_for_listening() { # PID LOG SCHEME: prints the URL without its closing /, or fails within 60 s
    local pid=$1 log=$2 scheme=$3 url=""
    for _ in $(seq 1 300); do
        kill -0 "$pid" 2>/dev/null || { cat "$log" >&2; fail "vots serve exited"; }
        url="$(sed -n "s|^vots serve: listening on \\($scheme://[^ ]*\\)/\$|\\1|p" "$log")"
        [[ -n $url ]] && { echo "$url"; return 0; }
        sleep 0.2
    done
    cat "$log" >&2
    fail "no 'listening on $scheme://' line within 60 s"
}
