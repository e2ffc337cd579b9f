# HAProxy 2.6 from Debian 12, for compose.yaml. Built locally (like the
# freeformd image) so the compose setup needs no registry, and its
# haproxy.cfg syntax matches the HAProxy version Debian 12 ships.
# (With a registry, the official image `haproxy:2.6` works the same way:
# mount haproxy.cfg at /usr/local/etc/haproxy/haproxy.cfg.)
FROM debian:bookworm

RUN apt-get update -q \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends haproxy \
 && rm -rf /var/lib/apt/lists/* /var/cache/apt/archives/*.deb \
 && mkdir -p /usr/local/etc/haproxy

COPY haproxy.cfg /usr/local/etc/haproxy/haproxy.cfg

USER haproxy
EXPOSE 50051
# SIGUSR1 = soft stop: stop accepting, let open streams finish.
STOPSIGNAL SIGUSR1
ENTRYPOINT ["haproxy", "-W", "-db", "-f", "/usr/local/etc/haproxy/haproxy.cfg"]
