// Our own declarations of the Unity native plug-in ABI that Drape uses (written from the
// description in shared docs/unity-notes.md section 2; not Unity's headers). Layouts must match
// Unity's exactly: plain structs of function pointers in this order.
#pragma once

#include <cstdint>

#if defined(_WIN32) || defined(_WIN64) || defined(WINAPI_FAMILY) || defined(__CYGWIN32__)
#define DRAPE_UNITY_API __stdcall
#define DRAPE_UNITY_EXPORT __declspec(dllexport)
#else
#define DRAPE_UNITY_API
#define DRAPE_UNITY_EXPORT __attribute__((visibility("default")))
#endif

namespace drape::unity {

struct InterfaceGUID {  // UnityInterfaceGUID: 16 bytes, high then low
    unsigned long long high;
    unsigned long long low;
};

/// IUnityInterfaces: exactly these 4 function pointers.
// Function-pointer types below use the plain C types the values travel as (void* for interface
// pointers, int for Unity's int-sized enums): the same ABI as Unity's headers, and the same type as
// a host declaring them so (UBSan's function check compares the types of calls through pointers).
struct Interfaces {
    void*(DRAPE_UNITY_API* GetInterface)(InterfaceGUID guid);
    void(DRAPE_UNITY_API* RegisterInterface)(InterfaceGUID guid, void* ptr);
    void*(DRAPE_UNITY_API* GetInterfaceSplit)(unsigned long long high, unsigned long long low);
    void(DRAPE_UNITY_API* RegisterInterfaceSplit)(unsigned long long high, unsigned long long low, void* ptr);
};

/// UnityGfxRenderer (values we look at).
enum GfxRenderer : int { kRendererNull = 4, kRendererOpenGLES30 = 11, kRendererOpenGLCore = 17 };
/// UnityGfxDeviceEventType.
enum GfxDeviceEventType : int { kEventInitialize = 0, kEventShutdown = 1, kEventBeforeReset = 2, kEventAfterReset = 3 };

/// Unity's parameter is UnityGfxDeviceEventType (int-sized).
using DeviceEventCallback = void(DRAPE_UNITY_API*)(int);
using RenderingEvent = void(DRAPE_UNITY_API*)(int event_id);

/// IUnityGraphics: exactly these 4 function pointers.
struct Graphics {
    int(DRAPE_UNITY_API* GetRenderer)();  ///< UnityGfxRenderer
    void(DRAPE_UNITY_API* RegisterDeviceEventCallback)(DeviceEventCallback callback);
    void(DRAPE_UNITY_API* UnregisterDeviceEventCallback)(DeviceEventCallback callback);
    int(DRAPE_UNITY_API* ReserveEventIDRange)(int count);
};
constexpr InterfaceGUID kGraphicsGUID{0x7CBA0A9CA4DDB544ULL, 0x8C5AD4926EB17B11ULL};

}  // namespace drape::unity

extern "C" {
DRAPE_UNITY_EXPORT void DRAPE_UNITY_API UnityPluginLoad(drape::unity::Interfaces* interfaces);
DRAPE_UNITY_EXPORT void DRAPE_UNITY_API UnityPluginUnload();
}
