#!/usr/bin/env bash
# Runs the .deb's postinst as on an installation, inside the private mount namespace that
# packaged_service.sh starts it in (unshare -m): /etc is a copy, /var/lib, /var/log and the sysusers.d
# and tmpfiles.d folders are empty tmpfs, so this machine's own files stay untouched. Checks the vots
# user, /etc/vots 0750 root:vots, a 0640 root:vots token that the vots user reads and others cannot, a
# second run changing nothing, and the packaged `vots` run as vots with the packaged configuration
# answering with that token.
#
# Usage (as root, in a private mount namespace): tests/install/postinst_check.sh WORK
#   WORK holds root/ (the .deb unpacked), control/ (its control files) and etc-copy/ (a copy of /etc).
set -euo pipefail
work=$1 root=$1/root
fail() { echo "packaged_service: FAIL: postinst: $*" >&2; exit 1; }
source "$(dirname "${BASH_SOURCE[0]}")/wait_for_listening.bash"

mount --bind "$work/etc-copy" /etc
mount -t tmpfs tmpfs /var/lib
mount -t tmpfs tmpfs /var/log
for dir in sysusers.d tmpfiles.d; do
    mkdir -p "/usr/lib/$dir" && mount -t tmpfs tmpfs "/usr/lib/$dir"
    cp "$root/usr/lib/$dir/vots.conf" "/usr/lib/$dir/"
done
mkdir -p /etc/vots && cp "$root/etc/vots/vots.conf" /etc/vots/
! getent passwd vots >/dev/null || fail "a vots user exists before the postinst (the copy of /etc?)"

sh "$work/control/postinst" configure "" >/dev/null 2>&1 || fail "postinst configure exited $?"
getent passwd vots | grep -q ':/var/lib/vots:/usr/sbin/nologin$' || fail "no vots system user: $(getent passwd vots)"
[[ "$(stat -c '%a %U:%G' /etc/vots)" == "750 root:vots" ]] || fail "/etc/vots is $(stat -c '%a %U:%G' /etc/vots)"
[[ "$(stat -c '%a %U:%G' /etc/vots/tokens)" == "640 root:vots" ]] || fail "/etc/vots/tokens is $(stat -c '%a %U:%G' /etc/vots/tokens)"
grep -qE '^operator operator [0-9a-f]{48}$' /etc/vots/tokens || fail "the made token file is not 'operator operator HEX'"
for dir in /var/lib/vots /var/lib/vots/data /var/lib/vots/cache /var/log/vots; do
    [[ "$(stat -c '%a %U:%G' "$dir")" == "750 vots:vots" ]] || fail "$dir is $(stat -c '%a %U:%G' "$dir")"
done
token_before="$(cat /etc/vots/tokens)"
sh "$work/control/postinst" configure "0.1.0" >/dev/null 2>&1 || fail "a second postinst configure exited $?"
[[ "$(cat /etc/vots/tokens)" == "$token_before" ]] || fail "a second postinst replaced the token"
! setpriv --reuid nobody --regid nogroup --clear-groups cat /etc/vots/tokens >/dev/null 2>&1 ||
    fail "another user reads /etc/vots/tokens"

# The service's process, less systemd's sandbox: the vots user, the packaged configuration, any free port.
chmod 755 "$work" # the unpacked binary and viewer under it, for the vots user
log="$work/postinst-serve.log"
: >"$log"
(cd /var/lib/vots && exec setpriv --reuid vots --regid vots --init-groups "$root/usr/bin/vots" serve \
    --config /etc/vots/vots.conf --port 0) >>"$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
url="$(wait_for_listening "$pid" "$log" http)"
token="$(awk '{print $3}' /etc/vots/tokens)"
curl -sf --max-time 30 -H "Authorization: Bearer $token" "$url/api/access" | grep -q '"role":"operator"' ||
    fail "vots serve as vots does not take the made token"
[[ "$(curl -s --max-time 30 -o /dev/null -w '%{http_code}' "$url/api/datasets")" == 401 ]] || fail "no token asked for"
kill "$pid" && wait "$pid" || fail "vots serve as vots did not stop cleanly"
trap - EXIT
echo "packaged_service: the postinst made the vots user, its folders and a 0640 root:vots token; vots serves with them"
