/* The catalogue CSV, parsed by libcsv (RFC 4180, strict quoting) and checked
 * row by row. See catalogue.h. */
#include "museum/catalogue.h"

#include <csv.h>
#include <errno.h>
#include <jansson.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/core.h"

enum { COL_FILE, COL_TITLE, COL_DATE, COL_HEIGHT, COL_DIAMETER, COL_DESCRIPTION, COL_COUNT };
static const char *const column_names[COL_COUNT] = {"file", "title", "date", "height_cm", "diameter_cm", "description"};

enum { MAX_FIELDS = 32, MAX_ROWS = 10000 };
#define MAX_BYTES (16L << 20)
#define MAX_SIZE_CM 1000.0

typedef struct {
    const char *csv_path;
    char folder[PATH_MAX];
    catalogue_t *cat;
    int column_of[MAX_FIELDS]; /* header field -> COL_*, from the first row */
    int n_header;
    char *fields[MAX_FIELDS];
    int n_fields, too_many;
    int row; /* 1-based, the header is row 1 */
    int failed;
    char *err;
    size_t errlen;
} parse_state;

static void fail(parse_state *s, const char *fmt, ...)
{
    if (s->failed)
        return;
    s->failed = 1;
    int n = snprintf(s->err, s->errlen, "%s: row %d: ", s->csv_path, s->row);
    va_list ap;
    va_start(ap, fmt);
    if (n >= 0 && (size_t)n < s->errlen)
        vsnprintf(s->err + n, s->errlen - (size_t)n, fmt, ap);
    va_end(ap);
}

static void on_field(void *data, size_t len, void *user)
{
    parse_state *s = user;
    if (s->failed)
        return;
    if (s->n_fields == MAX_FIELDS) {
        s->too_many = 1;
        return;
    }
    const char *text = data ? data : "";
    /* Labels become JSON, XML and cairo text: valid UTF-8 without NUL. */
    json_t *probe = json_stringn(text, len);
    if (!probe || strlen(text) != len) {
        json_decref(probe);
        s->row++;
        fail(s, "field %d is not UTF-8 text", s->n_fields + 1);
        return;
    }
    json_decref(probe);
    s->fields[s->n_fields] = strndup(text, len);
    if (!s->fields[s->n_fields]) {
        s->row++;
        fail(s, "out of memory");
        return;
    }
    s->n_fields++;
}

static int header_row(parse_state *s)
{
    int seen[COL_COUNT] = {0};
    for (int i = 0; i < s->n_fields; i++) {
        int col = -1;
        for (int c = 0; c < COL_COUNT; c++)
            if (!strcmp(s->fields[i], column_names[c]))
                col = c;
        if (col < 0) {
            fail(s, "unknown column '%s' (the columns are file, title, date, height_cm, diameter_cm, description)", s->fields[i]);
            return -1;
        }
        if (seen[col]++) {
            fail(s, "column '%s' appears twice", s->fields[i]);
            return -1;
        }
        s->column_of[i] = col;
    }
    if (!seen[COL_FILE]) {
        fail(s, "%s", "the header has no 'file' column");
        return -1;
    }
    s->n_header = s->n_fields;
    return 0;
}

/* A size column (height_cm, diameter_cm): centimetres, 0 < x <= 1000. */
static int parse_size(parse_state *s, int col, const char *text, double *cm)
{
    char *end;
    errno = 0;
    *cm = strtod(text, &end);
    if (end == text || *end || errno || !(*cm > 0.0 && *cm <= MAX_SIZE_CM)) {
        fail(s, "%s '%s' is not a length in centimetres (0 < x <= 1000)", column_names[col], text);
        return -1;
    }
    return 0;
}

static int entry_file(parse_state *s, const char *name, catalogue_entry *e)
{
    if (!*name) {
        fail(s, "%s", "the file column is empty");
        return -1;
    }
    int n = name[0] == '/' ? snprintf(e->path, sizeof e->path, "%s", name)
                           : snprintf(e->path, sizeof e->path, "%s%s", s->folder, name);
    struct stat st;
    if (n < 0 || (size_t)n >= sizeof e->path || stat(e->path, &st) != 0 || !realpath(e->path, e->real)) {
        fail(s, "file '%s' not found (%s)", name, e->path);
        return -1;
    }
    for (int i = 0; i < s->cat->n; i++)
        if (!strcmp(s->cat->entries[i].real, e->real)) {
            fail(s, "file '%s' is already catalogued", name);
            return -1;
        }
    return 0;
}

static char *take_nonempty(parse_state *s, int i)
{
    char *f = s->fields[i];
    if (!*f)
        return NULL;
    s->fields[i] = NULL;
    return f;
}

static void entry_row(parse_state *s)
{
    if (s->n_fields != s->n_header) {
        fail(s, "%d fields, but the header has %d", s->n_fields, s->n_header);
        return;
    }
    if (s->cat->n == MAX_ROWS) {
        fail(s, "more than %d rows", MAX_ROWS);
        return;
    }
    catalogue_entry e = {.height_cm = 0.0, .diameter_cm = 0.0};
    for (int i = 0; i < s->n_fields && !s->failed; i++) {
        switch (s->column_of[i]) {
        case COL_FILE: entry_file(s, s->fields[i], &e); break;
        case COL_TITLE: e.title = take_nonempty(s, i); break;
        case COL_DATE: e.date = take_nonempty(s, i); break;
        case COL_DESCRIPTION: e.description = take_nonempty(s, i); break;
        case COL_HEIGHT:
            if (*s->fields[i])
                parse_size(s, COL_HEIGHT, s->fields[i], &e.height_cm);
            break;
        case COL_DIAMETER:
            if (*s->fields[i])
                parse_size(s, COL_DIAMETER, s->fields[i], &e.diameter_cm);
            break;
        }
    }
    catalogue_entry *grown = s->failed ? NULL : realloc(s->cat->entries, (size_t)(s->cat->n + 1) * sizeof *grown);
    if (!grown) {
        free(e.title), free(e.date), free(e.description);
        fail(s, "%s", "out of memory");
        return;
    }
    s->cat->entries = grown;
    s->cat->entries[s->cat->n++] = e;
}

static void on_row(int terminator, void *user)
{
    (void)terminator;
    parse_state *s = user;
    if (!s->failed) {
        s->row++;
        if (s->too_many)
            fail(s, "more than %d fields", MAX_FIELDS);
        else if (s->row == 1)
            header_row(s);
        else
            entry_row(s);
    }
    for (int i = 0; i < s->n_fields; i++)
        free(s->fields[i]);
    s->n_fields = 0;
    s->too_many = 0;
}

/* 1 + the number of line breaks before offset. */
static int line_at(const char *text, size_t offset)
{
    int line = 1;
    for (size_t i = 0; i < offset; i++)
        line += text[i] == '\n';
    return line;
}

int catalogue_read(const char *path, catalogue_t *cat, char *err, size_t errlen)
{
    memset(cat, 0, sizeof *cat);
    char *text, why[256];
    size_t len;
    if (input_read_all(path, MAX_BYTES, &text, &len, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s: %s", path, why);
        return -1;
    }
    int rc = catalogue_parse(path, text, len, cat, err, errlen);
    free(text);
    return rc;
}

int catalogue_parse(const char *path, const char *text, size_t len, catalogue_t *cat, char *err, size_t errlen)
{
    memset(cat, 0, sizeof *cat);
    parse_state s = {.csv_path = path, .cat = cat, .err = err, .errlen = errlen};
    const char *slash = strrchr(path, '/');
    snprintf(s.folder, sizeof s.folder, "%.*s", slash ? (int)(slash - path) + 1 : 0, path);
    struct csv_parser p;
    if (csv_init(&p, CSV_STRICT | CSV_STRICT_FINI | CSV_APPEND_NULL) != 0) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    size_t done = csv_parse(&p, text, len, on_field, on_row, &s);
    int rc = done == len ? csv_fini(&p, on_field, on_row, &s) : -1;
    if (rc != 0 && !s.failed)
        snprintf(err, errlen, "%s: line %d: malformed CSV (%s)", path, line_at(text, done),
                 csv_error(&p) == CSV_EPARSE ? "a quote out of place or never closed" : csv_strerror(csv_error(&p)));
    for (int i = 0; i < s.n_fields; i++)
        free(s.fields[i]);
    csv_free(&p);
    if (rc == 0 && !s.failed && s.row == 0)
        snprintf(err, errlen, "%s: the catalogue is empty (it needs a header row)", path);
    if (rc != 0 || s.failed || s.row == 0) {
        catalogue_free(cat);
        return -1;
    }
    return 0;
}

const catalogue_entry *catalogue_find(const catalogue_t *cat, const char *photo_path)
{
    char real[PATH_MAX];
    if (!cat || !realpath(photo_path, real))
        return NULL;
    for (int i = 0; i < cat->n; i++)
        if (!strcmp(cat->entries[i].real, real))
            return &cat->entries[i];
    return NULL;
}

void catalogue_free(catalogue_t *cat)
{
    for (int i = 0; i < cat->n; i++) {
        free(cat->entries[i].title);
        free(cat->entries[i].date);
        free(cat->entries[i].description);
    }
    free(cat->entries);
    memset(cat, 0, sizeof *cat);
}
