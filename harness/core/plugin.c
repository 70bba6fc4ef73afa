/*
 * plugin.c: methods from shared libraries loaded at run time.
 *
 * A plug-in is built against aabench.h alone and exports `aa_plugin_abi` (equal to
 * AA_PLUGIN_ABI) and `aa_plugin_methods`, a NULL-terminated array of method
 * types.  It may call any public aa_ function: the aabench command exports
 * the whole library to it.  The library stays loaded until the process ends
 * (its type structs are in the table).
 */
#include "core.h"

#include <dlfcn.h>
#include <string.h>

int aa_plugin_load(const char *path)
{
    /* A name without a slash is a file in the current folder, as a user
     * means it, not a library for dlopen to search the system paths for. */
    char local[4096];
    if (!strchr(path, '/')) {
        if (aa_pathf(local, sizeof local, "./%s", path))
            return aa_fail_context(AA_EINVAL, "plug-in %s", aa_echo(path));
        path = local;
    }
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        /* dlerror() starts with the path itself: say it once */
        const char *why = dlerror();
        size_t n = strlen(path);
        if (!strncmp(why, path, n) && !strncmp(why + n, ": ", 2))
            why += n + 2;
        return aa_fail(AA_EIO, "plug-in %s: %s", aa_echo(path), why);
    }
    const int *abi = dlsym(lib, "aa_plugin_abi");
    const aa_method_type *const *types = dlsym(lib, "aa_plugin_methods");
    if (!abi || !types) {
        dlclose(lib);
        return aa_fail(AA_EINVAL, "plug-in %s exports no aa_plugin_abi or aa_plugin_methods",
                       aa_echo(path));
    }
    if (*abi != AA_PLUGIN_ABI) {
        int got = *abi;
        dlclose(lib);
        return aa_fail(AA_EINVAL, "plug-in %s was built for interface %d, this is %d",
                       aa_echo(path), got, AA_PLUGIN_ABI);
    }
    int st = aa_method_register(types, path);
    if (st)
        dlclose(lib);
    else
        st = aa_method_set_file(types, path);
    return st;
}
