#!/usr/bin/env bash
# Builds the .deb (cpack) and checks its service: the unit, sysusers.d, tmpfiles.d and /etc/vots/vots.conf
# are in it with their modes, the conffile and maintainer scripts are declared, `systemd-analyze verify`
# has nothing to say about the unit and `systemd-analyze security` rates its sandboxing OK, sysusers and
# tmpfiles make the user and folders, and the packaged vots serves HTTPS with the packaged configuration
# plus its two TLS lines; as root, the postinst runs in a private mount namespace (postinst_check.sh).
# Where systemd runs as PID 1 and VOTS_TEST_INSTALL_SERVICE=1 asks for it, it also installs the package
# on this machine, starts vots.service and asks it over TLS (then purges it).
#
# Usage: tests/install/packaged_service.sh BUILD_DIR      (ctest: Install.PackagedService)
# Deletes nothing but its own temporary folder (and, when asked to install, the package it installed).
set -euo pipefail

build="$(cd "$1" && pwd)"
work="$(mktemp -d "${TMPDIR:-/tmp}/vots-package-test.XXXXXX")"
server_pid=""
fail() { echo "packaged_service: FAIL: $*" >&2; exit 1; }
cleanup() {
    if [[ -n $server_pid ]]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP
source "$(dirname "${BASH_SOURCE[0]}")/wait_for_listening.bash"
for tool in cpack dpkg-deb systemd-analyze systemd-sysusers systemd-tmpfiles openssl curl; do
    command -v "$tool" >/dev/null || fail "$tool is missing (scripts/setup installs it)"
done

cpack --config "$build/CPackConfig.cmake" -B "$work/cpack" >"$work/cpack.log" 2>&1 || { cat "$work/cpack.log" >&2; fail "cpack"; }
debs=("$work"/cpack/vots_*.deb)
[[ -f ${debs[0]} ]] || fail "cpack made no vots_*.deb"
deb="${debs[0]}"
echo "packaged_service: built $(basename "$deb")"

# The files and their modes (`dpkg-deb -c`: mode, owner/group, size, date, time, path).
dpkg-deb -c "$deb" | awk '{print $1, $2, $6}' >"$work/contents"
expect_entry() { grep -qxF -- "$1 root/root ./$2" "$work/contents" || fail "the .deb lacks $1 ./$2: $(grep -F -- "./$2" "$work/contents" || echo absent)"; }
expect_entry -rwxr-xr-x usr/bin/vots
expect_entry -rw-r--r-- usr/lib/systemd/system/vots.service
expect_entry -rw-r--r-- usr/lib/sysusers.d/vots.conf
expect_entry -rw-r--r-- usr/lib/tmpfiles.d/vots.conf
expect_entry -rw-r--r-- etc/vots/vots.conf
expect_entry -rw-r--r-- usr/share/vots/web/index.html
# Secrets are made on the machine (postinst) or put there by its operator, never shipped.
[[ "$(grep -c ' \./etc/vots/.' "$work/contents")" == 1 ]] || fail "the .deb has more than vots.conf in /etc/vots: $(grep ' ./etc/' "$work/contents")"

dpkg-deb -e "$deb" "$work/control"
[[ "$(cat "$work/control/conffiles")" == /etc/vots/vots.conf ]] || fail "conffiles is not /etc/vots/vots.conf: $(cat "$work/control/conffiles")"
for script in postinst prerm postrm; do
    [[ "$(stat -c %a "$work/control/$script")" == 755 ]] || fail "$script is not mode 755"
    sh -n "$work/control/$script" || fail "$script is not a valid sh script"
done
dpkg-deb -f "$deb" Depends | grep -qw adduser || fail "Depends lacks adduser (the postinst's fallback)"

# docs/API.md ("As the packaged service") shows the configuration in full: the packaged one, word for word.
api_md="$(dirname "${BASH_SOURCE[0]}")/../../docs/API.md"
diff <(sed -n '/^# \/etc\/vots\/vots.conf:/,/^# tls-key/p' "$api_md") <(dpkg-deb --fsys-tarfile "$deb" | tar -xO ./etc/vots/vots.conf) >&2 ||
    fail "docs/API.md's copy of /etc/vots/vots.conf differs from the packaged one"

# The unit against the packaged tree plus this machine's own units (its targets) and /bin/kill.
root="$work/root"
dpkg-deb -x "$deb" "$root"
unit="$root/usr/lib/systemd/system/vots.service"
cp -n /usr/lib/systemd/system/*.target "$root/usr/lib/systemd/system/"
mkdir -p "$root/bin" && cp /bin/kill "$root/bin/kill"
verify="$(systemd-analyze verify --man=no --root="$root" vots.service 2>&1)" || fail "systemd-analyze verify: $verify"
# It warns about unknown keys and bad values and still exits 0: any word from it is a failure.
[[ -z $verify ]] || fail "systemd-analyze verify: $verify"
systemd-analyze security --offline=yes --root="$root" --threshold=20 vots.service >"$work/security" 2>&1 ||
    { cat "$work/security" >&2; fail "systemd-analyze security rates the sandboxing above 2.0"; }
grep 'Overall exposure' "$work/security"
grep -qx 'ExecStart=/usr/bin/vots serve --config /etc/vots/vots.conf' "$unit" || fail "the unit does not start vots serve --config /etc/vots/vots.conf"
grep -qx 'User=vots' "$unit" || fail "the unit does not run as vots"
# llvmpipe writes the machine code of its shaders and runs it.
! grep -q '^MemoryDenyWriteExecute' "$unit" || fail "MemoryDenyWriteExecute= would stop llvmpipe"

# The user and folders the postinst makes, made here under the packaged tree.
systemd-sysusers --root="$root" vots.conf >/dev/null 2>&1 || fail "systemd-sysusers vots.conf"
grep -q '^vots:x:[0-9]*:[0-9]*:.*:/var/lib/vots:/usr/sbin/nologin$' "$root/etc/passwd" || fail "no vots system user: $(cat "$root/etc/passwd")"
systemd-tmpfiles --root="$root" --create vots.conf 2>/dev/null || fail "systemd-tmpfiles vots.conf"
vots_uid="$(awk -F: '$1 == "vots" {print $3}' "$root/etc/passwd")"
for dir in var/lib/vots var/lib/vots/data var/lib/vots/cache var/log/vots; do
    [[ "$(stat -c '%a %u' "$root/$dir")" == "750 $vots_uid" ]] || fail "/$dir is not 0750 vots: $(stat -c '%a %u' "$root/$dir")"
done

# The packaged binary with the packaged configuration, its TLS lines uncommented and its paths moved into
# this test's folder: the file every installation starts from is accepted, and it serves HTTPS.
make_certificate() { # CA and a certificate for 127.0.0.1 in $1
    (cd "$1" && printf 'subjectAltName=IP:127.0.0.1\n' >san.ext &&
        openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -keyout ca.key -out ca.pem -days 2 -subj /CN=vots-test-ca &&
        openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -keyout key.pem -out cert.csr -subj /CN=127.0.0.1 &&
        openssl x509 -req -in cert.csr -CA ca.pem -CAkey ca.key -CAcreateserial -out cert.pem -days 2 -extfile san.ext) >/dev/null 2>&1 ||
        fail "openssl could not make the test certificate"
}
mkdir -p "$work/etc/tls" "$work/state/data" "$work/state/cache" "$work/log"
make_certificate "$work/etc/tls"
token="packaged-test-token-0123456789"
printf 'operator operator %s\n' "$token" >"$work/etc/tokens"
sed -e 's|^# tls-|tls-|' -e "s|/etc/vots/|$work/etc/|" -e "s|/var/lib/vots/|$work/state/|" -e "s|/var/log/vots/|$work/log/|" \
    -e 's|^port = 8080$|port = 0|' "$root/etc/vots/vots.conf" >"$work/etc/vots.conf"
grep -q "^tls-cert = $work/etc/tls/cert.pem$" "$work/etc/vots.conf" || fail "the packaged vots.conf has no '# tls-cert = /etc/vots/tls/cert.pem' line"
: >"$work/server.log"
"$root/usr/bin/vots" serve --config "$work/etc/vots.conf" >>"$work/server.log" 2>&1 &
server_pid=$!
url="$(wait_for_listening "$server_pid" "$work/server.log" https)"
curl -sf --max-time 30 --cacert "$work/etc/tls/ca.pem" -H "Authorization: Bearer $token" -o "$work/access.json" "$url/api/access" ||
    fail "GET /api/access over TLS with the token"
grep -q '"role":"operator"' "$work/access.json" || fail "/api/access: $(cat "$work/access.json")"
[[ "$(curl -s --max-time 30 --cacert "$work/etc/tls/ca.pem" -o /dev/null -w '%{http_code}' "$url/api/datasets")" == 401 ]] ||
    fail "the packaged configuration's token file is not asked for"
curl -sf --max-time 30 --cacert "$work/etc/tls/ca.pem" -H "Authorization: Bearer $token" -o /dev/null "$url/api/datasets" ||
    fail "GET /api/datasets over TLS"
for _ in $(seq 1 50); do grep -q '"action":"list-datasets"' "$work/log/audit.log" 2>/dev/null && break; sleep 0.1; done
grep -q '"action":"list-datasets"' "$work/log/audit.log" || fail "no audit line in the packaged configuration's audit log"
kill "$server_pid" && wait "$server_pid" || fail "the packaged server did not stop cleanly on SIGTERM"
server_pid=""
echo "packaged_service: the packaged vots.conf with its TLS lines serves $url"

# The postinst as on an installation, in a private mount namespace so that this machine stays as it was.
if [[ $(id -u) != 0 ]] || ! unshare -m --propagation private true 2>/dev/null; then
    echo "packaged_service: not running the postinst: it needs root and a private mount namespace (unshare -m)"
else
    cp -a /etc "$work/etc-copy"
    unshare -m --propagation private "$(dirname "${BASH_SOURCE[0]}")/postinst_check.sh" "$work" || exit 1
fi

# The real service, only where systemd is PID 1 (not in a container, where CI runs) and when asked for:
# it installs the package on this machine.
if [[ ! -d /run/systemd/system ]]; then
    echo "packaged_service: not starting vots.service: systemd is not PID 1 here (a container); the checks above ran"
elif [[ ${VOTS_TEST_INSTALL_SERVICE:-} != 1 || $(id -u) != 0 ]]; then
    echo "packaged_service: not starting vots.service: run as root with VOTS_TEST_INSTALL_SERVICE=1 to install the .deb here"
else
    trap 'systemctl stop vots.service || true; apt-get purge -y vots >/dev/null || true; cleanup' EXIT
    DEBIAN_FRONTEND=noninteractive apt-get install -y "$deb" >"$work/apt.log" 2>&1 || { cat "$work/apt.log" >&2; fail "apt-get install"; }
    install -d -o root -g vots -m 0750 /etc/vots/tls
    make_certificate /etc/vots/tls
    chown root:vots /etc/vots/tls/key.pem /etc/vots/tls/cert.pem && chmod 0640 /etc/vots/tls/key.pem /etc/vots/tls/cert.pem
    sed -i -e 's|^# tls-|tls-|' /etc/vots/vots.conf
    systemctl start vots.service || { journalctl -u vots --no-pager | tail -30 >&2; fail "systemctl start vots"; }
    token="$(awk '{print $3}' /etc/vots/tokens)"
    for _ in $(seq 1 150); do curl -sf --cacert /etc/vots/tls/ca.pem -o /dev/null https://127.0.0.1:8080/ && break; sleep 0.2; done
    curl -sf --max-time 30 --cacert /etc/vots/tls/ca.pem -H "Authorization: Bearer $token" https://127.0.0.1:8080/api/access |
        grep -q '"role":"operator"' || { journalctl -u vots --no-pager | tail -30 >&2; fail "vots.service does not answer over TLS"; }
    echo "packaged_service: vots.service answers https://127.0.0.1:8080/ as installed"
fi
echo "packaged_service: PASS"
