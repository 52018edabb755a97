#if DRAPE_HAS_INPUTSYSTEM && ENABLE_INPUT_SYSTEM
#define DRAPE_NEW_INPUT
#endif
using UnityEngine;
#if DRAPE_NEW_INPUT
using UnityEngine.InputSystem;
#endif

namespace Drape
{
    /// <summary>What one frame of pointer input hands to the cloth's drag (paper eq. 9): the touch
    /// point and its motion in screen pixels (origin bottom-left) plus the camera and object
    /// matrices (column-major, OpenGL convention, as drape.h will take them).</summary>
    public struct DrapeDragInput
    {
        public bool Active;
        public Vector2 ScreenPoint;
        public Vector2 ScreenDelta;
        public Rect PixelRect;
        public Matrix4x4 WorldToCamera;
        public Matrix4x4 Projection;
        public Matrix4x4 LocalToWorld;
    }

    /// <summary>Reads touch (or the mouse, in the editor and on desktop) and prepares the drag input
    /// of a <see cref="DrapeCloth"/> each frame: from the Input System when the package is installed
    /// and enabled, else from the legacy Input Manager.
    /// AWAITS NATIVE API: drape.h has no drag call yet; <see cref="Current"/> is filled every frame
    /// and not sent anywhere until it does. Nothing moves the cloth yet.</summary>
    [RequireComponent(typeof(DrapeCloth))]
    [AddComponentMenu("Drape/Drape Touch Drag")]
    public sealed class DrapeTouchDrag : MonoBehaviour
    {
        [Tooltip("Camera the touches are seen through; Camera.main when empty.")]
        public Camera Camera;

        [Tooltip("Drag strength (paper eq. 9 gain).")]
        [Range(0f, 10f)] public float Strength = 1f;

        [Tooltip("Falloff radius around the touch, in metres on the cloth (eq. 9, decreasing with distance).")]
        [Range(0.01f, 2f)] public float Radius = 0.2f;

        /// <summary>True once the native drag API exists; until then nothing is sent.</summary>
        public const bool NativeDragAvailable = false;

        private DrapeDragInput _current;
        private Vector2 _lastPoint;
        private bool _wasActive;

        /// <summary>This frame's drag input.</summary>
        public DrapeDragInput Current => _current;

        private void Update()
        {
            Camera cam = Camera != null ? Camera : Camera.main;
            bool active = ReadPointer(out Vector2 point);
            _current.Active = active && cam != null;
            _current.ScreenPoint = point;
            _current.ScreenDelta = active && _wasActive ? point - _lastPoint : Vector2.zero;
            _lastPoint = point;
            _wasActive = active;
            if (cam != null)
            {
                _current.PixelRect = cam.pixelRect;
                _current.WorldToCamera = cam.worldToCameraMatrix;
                _current.Projection = cam.projectionMatrix; // OpenGL convention, right for unprojection
            }
            _current.LocalToWorld = transform.localToWorldMatrix;
            if (_current.Active && _current.ScreenDelta != Vector2.zero)
            {
                var cloth = GetComponent<DrapeCloth>();
                if (cloth != null) cloth.WakeUp();
            }
        }

        private static bool ReadPointer(out Vector2 point)
        {
            point = Vector2.zero;
#if DRAPE_NEW_INPUT
            Touchscreen touch = Touchscreen.current;
            if (touch != null && touch.primaryTouch.press.isPressed)
            {
                point = touch.primaryTouch.position.ReadValue();
                return true;
            }
            Mouse mouse = Mouse.current;
            if (mouse != null && mouse.leftButton.isPressed)
            {
                point = mouse.position.ReadValue();
                return true;
            }
            return false;
#elif ENABLE_LEGACY_INPUT_MANAGER
            if (Input.touchCount > 0)
            {
                point = Input.GetTouch(0).position;
                return true;
            }
            if (Input.mousePresent && Input.GetMouseButton(0))
            {
                Vector3 m = Input.mousePosition;
                point = new Vector2(m.x, m.y);
                return true;
            }
            return false;
#else
            return false;
#endif
        }
    }
}
