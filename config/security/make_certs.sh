#!/bin/sh
# Throwaway certificates for a secured diffctl deployment (TLS with mutual certificates).
#
#   config/security/make_certs.sh DIR NAME[=SAN,SAN...] [NAME[=SAN...]]...
#
# Creates DIR/ca.pem + DIR/ca.key (once; reused on later runs) and, for each NAME, DIR/NAME.pem +
# DIR/NAME.key signed by that CA, with common name NAME (what an access-control rule matches in
# cert_common_names). SANs are IP addresses or DNS names a router is reached by, e.g.
#
#   config/security/make_certs.sh ~/diffctl-certs router-a=192.168.1.10 router-b=192.168.1.20 laptop
#
# Keys are EC P-256 and the certificates last 30 days (CERT_DAYS to change). Keep DIR private (chmod 700)
# and never commit it; copy ca.pem and one NAME.pem/NAME.key pair to each machine.
set -eu
if [ $# -lt 2 ]; then
  sed -n '4,5p' "$0" | sed 's/^# *//' >&2
  exit 2
fi
command -v openssl >/dev/null || { echo "make_certs.sh: openssl is missing (apt-get install openssl)" >&2; exit 2; }
dir=$1
shift
days=${CERT_DAYS:-30}
umask 077
mkdir -p "$dir"
if [ ! -f "$dir/ca.pem" ]; then
  openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days "$days" \
    -subj "/CN=diffctl-ca" -keyout "$dir/ca.key" -out "$dir/ca.pem" 2>/dev/null
fi
for spec in "$@"; do
  name=${spec%%=*}
  sans=""
  if [ "$spec" != "$name" ]; then
    for s in $(echo "${spec#*=}" | tr ',' ' '); do
      case $s in
        *:* | *[!0-9.]*) case $s in *:*) sans="$sans,IP:$s" ;; *) sans="$sans,DNS:$s" ;; esac ;;
        *) sans="$sans,IP:$s" ;;
      esac
    done
  fi
  sans="DNS:$name$sans"
  ext="$dir/$name.ext"
  printf 'subjectAltName=%s\nbasicConstraints=CA:FALSE\nextendedKeyUsage=serverAuth,clientAuth\n' "$sans" > "$ext"
  openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -subj "/CN=$name" \
    -keyout "$dir/$name.key" -out "$dir/$name.csr" 2>/dev/null
  openssl x509 -req -in "$dir/$name.csr" -CA "$dir/ca.pem" -CAkey "$dir/ca.key" -CAcreateserial \
    -days "$days" -extfile "$ext" -out "$dir/$name.pem" 2>/dev/null
  rm -f "$dir/$name.csr" "$ext"
  echo "$dir/$name.pem ($sans)"
done
