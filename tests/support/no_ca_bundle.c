/* The test processes open no TLS connection, yet Criterion initialises
 * libgit2 (for its assertion diffs) in every one of them, and libgit2's
 * mbedTLS backend then parses the system's whole CA bundle (220 KB of PEM;
 * under ASan, whose strstr measures the rest of the buffer at every
 * certificate, it is quadratic). Criterion runs each test in a process of
 * its own, so this definition, found before libmbedx509's by the dynamic
 * linker (the Makefile exports it), loads no certificate: libgit2 stays
 * initialised with an empty trust store (docs/BENCHMARKS.md, "Test suite"). */
struct mbedtls_x509_crt;

int mbedtls_x509_crt_parse_file(struct mbedtls_x509_crt *chain, const char *path);

int mbedtls_x509_crt_parse_file(struct mbedtls_x509_crt *chain, const char *path)
{
    (void)chain, (void)path;
    return 0;
}
