#!/bin/sh
# The container's entrypoint (docs/deploy.md): ncpostd in the foreground as PID 1's only child
# (exec), so SIGTERM reaches it and drains in-flight requests within NCPOST_SHUTDOWN_TIMEOUT.
# The admin token is read from a mounted file (a Docker or Kubernetes secret), never from the
# environment; the profile folder is used as the writable store when it is mounted writable.
# Extra arguments go to ncpostd.
set -eu
prefix=${NCPOST_PREFIX:-/opt/ncpost}
token_file=${NCPOST_ADMIN_TOKEN_FILE:-/run/secrets/ncpost-admin-token}
profiles=${NCPOST_PROFILES_DIR:-/var/lib/ncpost/profiles}

# A token in the environment would be visible to `docker inspect` and every child process.
unset NCPOST_ADMIN_TOKEN

set -- --listen "${NCPOST_LISTEN:-0.0.0.0:8080}" \
  --shutdown-timeout "${NCPOST_SHUTDOWN_TIMEOUT:-25}" "$@"
if [ -f "$token_file" ]; then
  set -- "$@" --admin-token-file "$token_file"
fi
if [ -d "$profiles" ] && [ -w "$profiles" ]; then
  set -- "$@" --profiles "$profiles"
fi
exec "$prefix/bin/ncpostd" "$@"
