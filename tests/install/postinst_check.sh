#!/usr/bin/env bash
# Runs the .deb's postinst as on an installation, inside the private mount namespace that
# packaged_service.sh starts it in (unshare -m): /etc is a copy, /var/lib, /var/log and the sysusers.d
# and tmpfiles.d folders are empty tmpfs, so this machine's own files stay untouched. Checks the vots
# user, /etc/vots 0750 root:vots, a 0640 root:vots token that the vots user reads and others cannot, a
# second run changing nothing, and the packaged `vots` run as vots with the packaged configuration, in
# part of the unit's sandbox, answering with that token and drawing a frame.
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

# The service's process with what of the unit's sandbox a mount namespace gives: a /dev of the nodes
# PrivateDevices= leaves (no /dev/dri: llvmpipe renders on the CPU), the file system read-only but for
# /var/lib/vots and /var/log/vots (ProtectSystem=strict), no new privileges, the vots user and its home;
# the packaged configuration on any free port, and a tiny volume to draw.
chmod 755 "$work" # the unpacked binary and viewer under it, for the vots user
{
    printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n\n'
    head -c 512 /dev/urandom
} >/var/lib/vots/data/tiny.nrrd
chown vots:vots /var/lib/vots/data/tiny.nrrd
log="$work/postinst-serve.log"
: >"$log"
mount --bind "$work" "$work" # stays writable for the log when / is made read-only
mkdir -p "$work/host-dev"
mount --bind /dev "$work/host-dev"
mount -t tmpfs -o mode=755 tmpfs /dev
for node in null zero full random urandom tty; do
    touch "/dev/$node" && mount --bind "$work/host-dev/$node" "/dev/$node"
done
mkdir /dev/shm && mount -t tmpfs -o mode=1777 tmpfs /dev/shm
mount -o remount,bind,ro / && mount -o remount,bind,ro /etc || fail "cannot make / and /etc read-only here"
(cd /var/lib/vots && exec env HOME=/var/lib/vots setpriv --reuid vots --regid vots --init-groups --no-new-privs \
    "$root/usr/bin/vots" serve --config /etc/vots/vots.conf --port 0) >>"$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
url="$(wait_for_listening "$pid" "$log" http)"
token="$(awk '{print $3}' /etc/vots/tokens)"
curl -sf --max-time 30 -H "Authorization: Bearer $token" "$url/api/access" | grep -q '"role":"operator"' ||
    fail "vots serve as vots does not take the made token"
[[ "$(curl -s --max-time 30 -o /dev/null -w '%{http_code}' "$url/api/datasets")" == 401 ]] || fail "no token asked for"
[[ ! -e /dev/dri ]] || fail "/dev/dri is there"
curl -sf --max-time 120 -H "Authorization: Bearer $token" -o "$work/tiny.png" "$url/render?dataset=tiny&size=32x32" ||
    { cat "$log" >&2; fail "/render did not answer 200 without /dev/dri on a read-only system"; }
[[ "$(head -c 8 "$work/tiny.png" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "/render is not a PNG"
grep -q '"action":"render"' /var/log/vots/audit.log || fail "no render line in /var/log/vots/audit.log"
kill "$pid" && wait "$pid" || fail "vots serve as vots did not stop cleanly"
trap - EXIT
echo "packaged_service: the postinst made the vots user, its folders and a 0640 root:vots token; vots serves" \
    "with them and draws without /dev/dri on a read-only system"
