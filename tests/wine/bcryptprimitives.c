/* A stand-in for Windows' bcryptprimitives.dll, for tests under wine 8.0 only (Debian bookworm's
 * wine64 has no bcryptprimitives.dll; wine 9 and every Windows 10 and later have it). Rust's std
 * calls ProcessPrng from it for random seeds (HashMap). Here it is RtlGenRandom from advapi32.
 * It is placed beside the test's importer.exe, never packed into an FMU.
 * Build: zig cc -target x86_64-windows-gnu -shared -o bcryptprimitives.dll bcryptprimitives.c -ladvapi32 */
#include <windows.h>
#include <ntsecapi.h>

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length) {
    while (length > 0) {
        ULONG n = length > 0x10000000 ? 0x10000000 : (ULONG)length;
        if (!RtlGenRandom(data, n)) {
            return FALSE;
        }
        data += n;
        length -= n;
    }
    return TRUE;
}
