# Sourced by the scripts that render a page in headless Chromium. `headless_serve DIR CLEANUP`
# serves DIR on a random loopback port ($port), makes a Chromium profile for the run and the
# flags every run takes ($headless, an array), and on exit stops the server, removes the
# profile and runs CLEANUP (a command, evaluated then).
headless_serve() {
  port=$((20000 + RANDOM % 10000))
  node "$(dirname "${BASH_SOURCE[0]}")/serve.js" "$1" "$port" &
  server=$!
  profile="$(mktemp -d)"
  trap "kill $server 2>/dev/null; rm -rf '$profile'; $2" EXIT
  sleep 1
  headless=(--headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader
    --disable-quic --no-first-run --disable-background-networking --disable-component-update
    --disable-sync --user-data-dir="$profile")
}
