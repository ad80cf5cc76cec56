#!/usr/bin/env bash
# Install the npm packages of web/ (three.js for the viewer pages, esbuild to
# bundle them, playwright-core for the browser tests), exactly as pinned in
# web/package-lock.json, with 'npm ci'.  Does nothing when web/node_modules
# already matches the lock file.  Needs node and npm (Debian's nodejs and npm);
# as root it installs npm when it is missing.  With a directory argument, the
# same for the npm packages of that directory (bench/nonconvex: Manifold).
set -euo pipefail
web=$(cd "${1:-$(dirname "$0")/../web}" && pwd)
stamp="$web/node_modules/.minksum-lock"
if [ -f "$stamp" ] && cmp -s "$stamp" "$web/package-lock.json"; then
  exit 0
fi
if ! command -v npm >/dev/null 2>&1; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "setup-web: installing npm"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends npm
  else
    echo "setup-web: npm is missing; run 'sudo apt-get install npm' or run make as root" >&2
    exit 1
  fi
fi
echo "setup-web: npm ci in $web"
(cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
cp "$web/package-lock.json" "$stamp"
