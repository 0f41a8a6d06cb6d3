/* fuzz_md.c - the fuzz target of the modelDescription.xml reader (tools/fmi/fmu_md.c): any
 * bytes as a model description. What parses is walked whole (every string, every model
 * structure reference resolved), so the reader cannot hand the importer a dangling
 * pointer or an index out of range; nothing may crash, leak, read out of bounds or hit
 * undefined behaviour (libFuzzer with ASan and UBSan, or tests/scenec/fuzz_main.c). */
#include <stdint.h>
#include <string.h>

#include "fmu_md.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static size_t len(const char *s) { return s ? strlen(s) : 0; }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fmu_md md;
    char err[FMU_ERR_LEN];
    volatile size_t sink = 0;
    if (fmu_md_parse((const char *)data, size, &md, err, sizeof err) == 0) {
        sink += len(md.fmi_version) + len(md.model_name) + len(md.token) + len(md.me_id);
        for (uint32_t i = 0; i < md.nv; i++)
            sink += len(md.v[i].name) + len(md.v[i].unit) + len(md.v[i].type) +
                    len(md.v[i].desc) + (size_t)(md.v[i].derivative >= 0 &&
                                                fmu_md_find(&md, md.v[i].derivative) >= 0);
        for (uint32_t i = 0; i < md.nder; i++)
            sink += md.v[fmu_md_find(&md, md.der[i])].vr;
        for (uint32_t i = 0; i < md.nout; i++) {
            sink += md.v[fmu_md_find(&md, md.out[i].ref)].vr;
            for (uint32_t j = 0; j < md.out[i].ndeps; j++)
                sink += (size_t)fmu_md_find(&md, md.out[i].deps[j]);
        }
    } else {
        sink += strlen(err);
    }
    fmu_md_free(&md);
    (void)sink;
    return 0;
}
