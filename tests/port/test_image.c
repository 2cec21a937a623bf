/* SPDX-License-Identifier: MIT */
/* test_image.c: images in memory and the frame hash that test-cross and the mps2-an386 firmware compare. */
#include <string.h>

#include "check.h"
#include "render/image.h"

static void hash_is_fnv1a_64_over_the_pixel_bytes(void)
{
    /* FNV-1a 64 of "abc" is 0xe71fa2190541574b (the published test vector); of nothing, the offset basis. */
    uint8_t px[8] = {'a', 'b', 'c', 0x55, 0x55, 0x55, 0x55, 0x55};
    vf_image_t one = {px, 1, 1, 3, VF_FORMAT_RGB888};
    CHECK(vfp_image_hash(&one) == UINT64_C(0xe71fa2190541574b));
    vf_image_t none = {px, 0, 0, 0, VF_FORMAT_RGB888};
    CHECK(vfp_image_hash(&none) == UINT64_C(0xcbf29ce484222325));
    /* The stride's padding is not hashed: two rows of "abc" with 5 bytes of anything between them. */
    uint8_t padded[11] = {'a', 'b', 'c', 1, 2, 3, 4, 5, 'a', 'b', 'c'}, packed[6] = {'a', 'b', 'c', 'a', 'b', 'c'};
    vf_image_t p1 = {padded, 1, 2, 8, VF_FORMAT_RGB888}, p2 = {packed, 1, 2, 3, VF_FORMAT_RGB888};
    CHECK(vfp_image_hash(&p1) == vfp_image_hash(&p2));
    padded[9] ^= 1; /* one bit of a pixel changes it */
    CHECK(vfp_image_hash(&p1) != vfp_image_hash(&p2));
}

static void alloc_and_free(void)
{
    vf_image_t img;
    CHECK_EQ(vfp_image_alloc(&img, 5, 3, VF_FORMAT_RGB565), 0);
    CHECK_EQ(img.stride, 10);
    CHECK(img.pixels != NULL);
    CHECK(((uint8_t *)img.pixels)[29] == 0); /* zeroed */
    vfp_image_free(&img);
    CHECK(img.pixels == NULL);
    vfp_image_free(&img); /* twice is harmless */
}

CHECK_CASES({"hash_is_fnv1a_64_over_the_pixel_bytes", hash_is_fnv1a_64_over_the_pixel_bytes},
            {"alloc_and_free", alloc_and_free});
CHECK_RUN("port/image")
