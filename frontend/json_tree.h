/* json_tree.h -- a small JSON reader for the launcher: the run's summary.json
 * as a tree of nodes over the text (strings and numbers point into it).
 *
 * bk_json_parse(text, len, tree)  in: the text (kept while the tree is used);
 *                                 out: the tree (bk_json_free releases it).
 *                                 Returns 0, or -1 for text that is not JSON.
 * bk_json_get(tree, obj, "key")   the value of a member (index), or -1
 * Node 0 is the document's value. */
#ifndef BK_JSON_TREE_H
#define BK_JSON_TREE_H

#include <stddef.h>

enum { BK_JNULL, BK_JFALSE, BK_JTRUE, BK_JNUM, BK_JSTR, BK_JARR, BK_JOBJ };

typedef struct {
    int type;
    const char *text;         /* a string's characters (between the quotes, escapes as written) or a number's */
    size_t len;
    int first, next;          /* first child / next sibling (-1: none); an object's children alternate key, value */
    int count;                /* children of an array; members of an object */
} bk_jnode;

typedef struct {
    bk_jnode *node;
    int n, cap;
} bk_json;

int bk_json_parse(const char *text, size_t len, bk_json *t);
void bk_json_free(bk_json *t);
int bk_json_get(const bk_json *t, int obj, const char *key);
double bk_json_num(const bk_json *t, int i);       /* a number's value (NaN for anything else) */
int bk_json_truthy(const bk_json *t, int i);       /* Python's truth of the value */

#endif
