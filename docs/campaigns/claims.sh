#!/bin/sh
# Remake docs/campaigns/paper/claims.md (and claims.csv beside it) from the committed analyses.
# Usage: docs/campaigns/claims.sh BINARY
# The binary must be built from a clean tree: claims.md names the build that made it, and a table made by a
# build with uncommitted changes cannot be made again by anyone.
set -eu
bin=${1:?usage: docs/campaigns/claims.sh BINARY}
cd "$(dirname "$0")/../.."
version=$("$bin" --version)
case "$version" in
*dirty*)
  echo "claims.sh: $bin was built from a tree with uncommitted changes ($version): commit, rebuild, run again" >&2
  exit 2
  ;;
esac
"$bin" claims literal=docs/campaigns/paper/analysis vibrated=docs/campaigns/paper-vibrated/analysis \
  --column literal=docs/campaigns/column --column vibrated=docs/campaigns/column-vibrated \
  --out docs/campaigns/paper/claims.md --force
