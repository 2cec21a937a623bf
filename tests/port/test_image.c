/* SPDX-License-Identifier: MIT */
/* test_image.c: images in memory and the frame hash that test-cross and the mps2-an386 firmware compare. */
#include <string.h>

#include "check.h"
#include "io/pngio.h"
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

/* vfp_image_to_rgb (io/pngio.h): every RGB565 word, in a 256x256 image with a padded stride, to the 8 bits of
 * each field rounded to nearest; RGB888 copied and XRGB8888 reordered, pixel by pixel. */
static void to_rgb_every_format(void)
{
    static uint8_t px[256 * 516], rgb[256 * 256 * 3];
    for (unsigned w = 0; w < 65536; w++) {
        px[(w >> 8) * 516 + (w & 255) * 2] = (uint8_t)(w & 255);
        px[(w >> 8) * 516 + (w & 255) * 2 + 1] = (uint8_t)(w >> 8);
    }
    vf_image_t img = {px, 256, 256, 516, VF_FORMAT_RGB565};
    vfp_image_to_rgb(&img, rgb);
    for (unsigned w = 0; w < 65536; w++) {
        const uint8_t *o = rgb + (size_t)w * 3;
        const unsigned r = ((w >> 11) * 255 + 15) / 31, g = (((w >> 5) & 63) * 255 + 31) / 63,
                       b = ((w & 31) * 255 + 15) / 31;
        CHECK_MSG(o[0] == r && o[1] == g && o[2] == b, "565 word %04x: %u %u %u, want %u %u %u", w, o[0], o[1], o[2], r,
                  g, b);
    }
    CHECK(rgb[0] == 0 && rgb[65535 * 3] == 255 && rgb[65535 * 3 + 1] == 255 && rgb[65535 * 3 + 2] == 255);
    for (size_t i = 0; i < sizeof px; i++)
        px[i] = (uint8_t)(i * 7 + (i >> 9));
    img = (vf_image_t){px, 100, 3, 400, VF_FORMAT_RGB888};
    vfp_image_to_rgb(&img, rgb);
    for (unsigned y = 0; y < 3; y++)
        CHECK(memcmp(rgb + y * 300, px + y * 400, 300) == 0);
    img = (vf_image_t){px, 100, 3, 400, VF_FORMAT_XRGB8888};
    vfp_image_to_rgb(&img, rgb);
    for (unsigned y = 0; y < 3; y++)
        for (unsigned x = 0; x < 100; x++) {
            const uint8_t *i = px + y * 400 + x * 4, *o = rgb + (y * 100 + x) * 3;
            CHECK(o[0] == i[2] && o[1] == i[1] && o[2] == i[0]);
        }
}

CHECK_CASES({"hash_is_fnv1a_64_over_the_pixel_bytes", hash_is_fnv1a_64_over_the_pixel_bytes},
            {"alloc_and_free", alloc_and_free}, {"to_rgb_every_format", to_rgb_every_format});
CHECK_RUN("port/image")
