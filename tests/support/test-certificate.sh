# Sourced by the shell tests that serve HTTPS: make_test_certificate DIR writes DIR/ca.pem (a test CA made
# here) and DIR/site.pem, DIR/site.key (a certificate for 127.0.0.1 signed by it).
make_test_certificate() {
    local dir=$1
    local ec=(-newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes)
    openssl req -x509 "${ec[@]}" -keyout "$dir/ca.key" -out "$dir/ca.pem" -days 2 -subj /CN=vots-test-ca 2>/dev/null
    openssl req "${ec[@]}" -keyout "$dir/site.key" -out "$dir/site.csr" -subj /CN=127.0.0.1 2>/dev/null
    printf 'subjectAltName=IP:127.0.0.1\n' >"$dir/san.ext"
    openssl x509 -req -in "$dir/site.csr" -CA "$dir/ca.pem" -CAkey "$dir/ca.key" -CAcreateserial \
        -out "$dir/site.pem" -days 2 -extfile "$dir/san.ext" 2>/dev/null
}
