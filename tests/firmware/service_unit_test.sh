#!/usr/bin/env bash
# The package's systemd unit: systemd's own checker finds nothing to say about it (with ExecStart
# pointed at the built irlocd, since /usr/bin/irlocd is not installed here), its offline security
# exposure stays at most 2.0 (docs/hardware.md has the table), and it keeps the supervision and
# hardening keys docs/hardware.md promises.
# Usage: service_unit_test.sh SOURCE_DIR IRLOCD
set -euo pipefail
unit="${1:?usage: $0 SOURCE_DIR IRLOCD}/tools/deb/irlocd.service"
irlocd=${2:?usage: $0 SOURCE_DIR IRLOCD}
work=$(mktemp -d "${TMPDIR:-/tmp}/irloc-unit.XXXXXX")
trap 'rm -rf "$work"' EXIT
failed=0

sed "s|^ExecStart=/usr/bin/irlocd |ExecStart=$irlocd |" "$unit" > "$work/irlocd.service"
grep -q "^ExecStart=$irlocd " "$work/irlocd.service" || { echo "FAIL: ExecStart=/usr/bin/irlocd not found in $unit"; exit 1; }
# verify reports unknown keys and bad values as warnings with status 0: any output is a failure.
if ! output=$(systemd-analyze verify "$work/irlocd.service" 2>&1) || [ -n "$output" ]; then
  echo "FAIL: systemd-analyze verify $unit:"; echo "$output"; failed=1
fi
# --threshold: exposure x 10; 1.7 when written.
if ! systemd-analyze security --offline=yes --threshold=20 "$unit" > "$work/security.txt" 2>&1; then
  echo "FAIL: systemd-analyze security: exposure above 2.0:"; tail -1 "$work/security.txt"; failed=1
fi
for key in Type=notify NotifyAccess=main 'WatchdogSec=[1-9]' Restart=on-failure User=irlocd NoNewPrivileges=yes \
           ProtectSystem=strict ProtectHome=yes PrivateTmp=yes StateDirectory=irlocd 'ExecReload=/bin/kill -HUP'; do
  grep -qE "^$key" "$unit" || { echo "FAIL: $unit: no $key"; failed=1; }
done
[ "$failed" = 0 ] && echo "irlocd.service: verify clean, $(tail -1 "$work/security.txt" | sed 's/^→ //')"
exit "$failed"
