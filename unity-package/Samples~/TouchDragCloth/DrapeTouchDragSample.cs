using UnityEngine;

namespace Drape.Samples.TouchDrag
{
    /// <summary>Drape sample "Touch-drag cloth": add this to an empty GameObject in an empty scene and
    /// press Play (or build to a phone). A curtain hangs from its top edge in front of the camera;
    /// drag it with a finger or the mouse (paper eq. 9: the cloth near the finger follows it), or
    /// switch the Drape Touch Drag component to Grab to pick a vertex and hold it. The Drape HUD shows
    /// step time, model, backend and vertex count.</summary>
    [AddComponentMenu("Drape/Samples/Touch Drag Cloth")]
    public sealed class DrapeTouchDragSample : MonoBehaviour
    {
        [Tooltip("Drag (eq. 9 falloff) or Grab (pick and hold one vertex).")]
        public DrapeTouchMode Mode = DrapeTouchMode.Drag;

        [Tooltip("Backend for the curtain. Auto uses the GPU on an OpenGL ES 3 device when the library has it.")]
        public DrapeBackendChoice Backend = DrapeBackendChoice.Auto;

        private void Start()
        {
            Camera cam = SampleSetup.CameraAndLight(new Vector3(0f, 1f, -2.6f), new Vector3(0f, 1f, 0f));

            var curtain = new GameObject("Curtain");
            curtain.SetActive(false);
            curtain.transform.position = new Vector3(0f, 1.75f, 0f);
            curtain.AddComponent<MeshFilter>();
            var primitive = GameObject.CreatePrimitive(PrimitiveType.Quad);
            curtain.AddComponent<MeshRenderer>().sharedMaterial = primitive.GetComponent<MeshRenderer>().sharedMaterial;
            Destroy(primitive);
            var cloth = curtain.AddComponent<DrapeCloth>();
            cloth.Columns = 48;
            cloth.Rows = 48;
            cloth.Size = new Vector2(1.5f, 1.5f);
            cloth.PinMode = DrapePinMode.TopEdge;
            cloth.Backend = Backend;
            cloth.AirDrag = 0.5f;
            var drag = curtain.AddComponent<DrapeTouchDrag>();
            drag.Camera = cam;
            drag.Mode = Mode;
            curtain.SetActive(true);

            gameObject.AddComponent<DrapeHud>().Cloth = cloth;
        }
    }
}
