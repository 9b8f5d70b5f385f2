#!/bin/sh
# The command-line tool and the Python module are clients of the library like any other program:
# they use only its public API (include/contactqp/), never a detail:: name or an internal header
# of src/ (their own folder's headers are theirs). ctest: cli_and_python_use_the_public_api.
set -eu
cd "$(dirname "$0")/.."
status=0
if grep -rn 'detail::' src/cli python/src; then
  echo "check-public-api: the lines above use a detail:: name of the library" >&2
  status=1
fi
if grep -rnE '#include "[^"]+/' src/cli python/src | grep -v '#include "contactqp/'; then
  echo "check-public-api: the lines above include an internal header of the library" >&2
  status=1
fi
exit $status
