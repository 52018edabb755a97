#if DRAPE_HAS_INPUTSYSTEM && ENABLE_INPUT_SYSTEM
#define DRAPE_NEW_INPUT
#endif
using Drape.Core;
using UnityEngine;
#if DRAPE_NEW_INPUT
using UnityEngine.InputSystem;
#endif

namespace Drape
{
    /// <summary>How a finger moves the cloth.</summary>
    public enum DrapeTouchMode
    {
        /// <summary>The paper's touch drag (eq. 9): vertices near the finger follow its motion with a
        /// Gaussian falloff in screen space (drape_cloth_drag). Works on every backend.</summary>
        Drag = 0,
        /// <summary>Pick-and-hold: the vertex nearest the finger is held under it as a moving pin
        /// until release (drape_cloth_grab). Every backend (a GPU cloth picks on the GPU).</summary>
        Grab = 1,
    }

    /// <summary>Moves a <see cref="DrapeCloth"/> with touch (or the mouse, in the editor and on
    /// desktop): the Input System when the package is installed and enabled, else the legacy Input
    /// Manager. Each frame it passes the touch point, the finger's motion, the cloth's
    /// simulation-to-world matrix and the camera's view and projection matrices (column-major,
    /// OpenGL convention: Camera.projectionMatrix) and viewport to the native side. The drag applies
    /// over the cloth's next step. No allocation per frame.</summary>
    [RequireComponent(typeof(DrapeCloth))]
    [DisallowMultipleComponent]
    [AddComponentMenu("Drape/Drape Touch Drag")]
    [HelpURL(DrapeDocs.Manual + "#drapetouchdrag")]
    public sealed class DrapeTouchDrag : MonoBehaviour
    {
        [Tooltip("Camera the touches are seen through; Camera.main when empty.")]
        public Camera Camera;

        [Tooltip("Drag: vertices near the finger follow it (paper eq. 9). Grab: the nearest vertex is held under the finger.")]
        public DrapeTouchMode Mode = DrapeTouchMode.Drag;

        [Tooltip("Drag: eq. 9's A. With sigma it sets the radius within which vertices follow the finger fully: sqrt(2 sigma ln A) px.")]
        [Range(1f, 1000f)] public float Amplitude = 200f;

        [Tooltip("Drag: eq. 9's sigma, px^2 (a variance). 300 px^2 with A = 200: full follow within 56 px, none beyond ~80 px.")]
        [Range(10f, 20000f)] public float Sigma = 300f;

        [Tooltip("Grab: how far from the finger (px) a vertex may be picked.")]
        [Range(1f, 200f)] public float PickRadius = 40f;

        [Tooltip("Treat the pixel values above as pixels of a 96 dpi screen and scale them by Screen.dpi, so the " +
                 "finger's reach is the same size in millimetres on every device (56 px at 96 dpi is about 15 mm).")]
        public bool ScaleWithScreenDensity = true;

        /// <summary>The screen density the pixel settings are given for (a desktop monitor's).</summary>
        public const float ReferenceDpi = 96f;

        /// <summary>Factor from reference pixels to this screen's pixels: dpi / 96; 1 where Unity does not
        /// know the density (Screen.dpi is 0).</summary>
        public static float DensityScale(float dpi) => dpi > 0f && !float.IsInfinity(dpi) ? dpi / ReferenceDpi : 1f;

        private const uint GrabId = 0;

        private DrapeCloth _cloth;
        private readonly Drape.Core.TouchPoint[] _touches = new Drape.Core.TouchPoint[1];
        private Vector2 _lastPoint;
        private bool _wasActive;
        private bool _holding;

        /// <summary>The vertex held in Grab mode, or <see cref="NativeCloth.NoVertex"/>; on a GPU cloth
        /// <see cref="NativeCloth.GrabOnGpu"/> while the finger is down (the vertex is picked on the GPU).</summary>
        public uint HeldVertex { get; private set; } = NativeCloth.NoVertex;

        private void OnEnable() => _cloth = GetComponent<DrapeCloth>();

        private void OnDisable()
        {
            Release();
            _wasActive = false;
        }

        private void Update()
        {
            NativeCloth cloth = _cloth != null ? _cloth.NativeCloth : null;
            Camera cam = Camera != null ? Camera : Camera.main;
            bool active = ReadPointer(out Vector2 screen) && cam != null && cloth != null;
            if (!active)
            {
                Release();
                _wasActive = false;
                return;
            }

            // drape_view: pixels relative to the camera's viewport, origin bottom-left.
            Rect rect = cam.pixelRect;
            var point = new Vector2(screen.x - rect.x, screen.y - rect.y);
            var view = new View
            {
                World = DrapeConvert.ToDrape(_cloth.SimulationToWorld),
                ViewMatrix = DrapeConvert.ToDrape(cam.worldToCameraMatrix),
                Projection = DrapeConvert.ToDrape(cam.projectionMatrix), // OpenGL convention, as drape.h wants
                Viewport = new Float2(rect.width, rect.height),
            };
            float scale = ScaleWithScreenDensity ? DensityScale(Screen.dpi) : 1f;
            try
            {
                if (Mode == DrapeTouchMode.Grab)
                {
                    if (!_wasActive)
                    {
                        HeldVertex = cloth.Grab(view, GrabId, new Float2(point.x, point.y), PickRadius * scale);
                        _holding = HeldVertex != NativeCloth.NoVertex; // GrabOnGpu: held until released
                    }
                    else if (_holding && point != _lastPoint)
                    {
                        cloth.GrabMove(view, GrabId, new Float2(point.x, point.y));
                    }
                }
                else if (_wasActive && point != _lastPoint)
                {
                    _touches[0] = new Drape.Core.TouchPoint
                    {
                        Position = new Float2(_lastPoint.x, _lastPoint.y), // where the finger was
                        Motion = new Float2(point.x - _lastPoint.x, point.y - _lastPoint.y),
                        Amplitude = Amplitude,
                        Sigma = Sigma * scale * scale, // a variance: px^2
                    };
                    cloth.Drag(view, _touches);
                }
            }
            catch (DrapeException e)
            {
                Debug.LogException(e, this);
                enabled = false;
            }
            _lastPoint = point;
            _wasActive = true;
        }

        private void Release()
        {
            if (!_holding) return;
            _holding = false;
            HeldVertex = NativeCloth.NoVertex;
            NativeCloth cloth = _cloth != null ? _cloth.NativeCloth : null;
            if (cloth != null && !cloth.IsDisposed) cloth.GrabRelease(GrabId);
        }

        /// <summary>The primary touch, else the left mouse button, in screen pixels (origin bottom-left).</summary>
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
